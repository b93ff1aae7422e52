"""``/docs``: the API described from ``/openapi.json`` on one self-contained page.

FastAPI's Swagger UI loads its script and style from a CDN (cdn.jsdelivr.net), so on a
machine without internet access, or behind a policy that allows this origin only, ``/docs``
was a blank page. This page is built on the server from the same OpenAPI document: every
route with its methods, summary, parameters and body types, no script, nothing fetched.
"""

from __future__ import annotations

import html

__all__ = ["api_reference_html", "API_DOC_CSP"]

#: Inline style only; no script, no other origin.
API_DOC_CSP = ("default-src 'none'; style-src 'unsafe-inline'; base-uri 'none'; "
               "form-action 'none'; frame-ancestors 'none'")

_STYLE = """
body { font-family: system-ui, sans-serif; margin: 1em 2em; color: #222; }
h1 { font-size: 1.5em; } h2 { font-size: 1.05em; margin: 1.4em 0 0.3em; font-family: monospace; }
.m { display: inline-block; min-width: 4.5em; font-weight: bold; color: #1b4f8a; }
p { margin: 0.2em 0; max-width: 60em; } .muted { color: #666; }
table { border-collapse: collapse; font-size: 0.9em; margin: 0.3em 0; }
th, td { border: 1px solid #ddd; padding: 0.2em 0.5em; text-align: left; vertical-align: top; }
th { background: #eef1f5; } td.d { max-width: 50em; }
"""


def _e(text) -> str:
    return html.escape(str(text), quote=True)


def _parameters(params: list[dict]) -> str:
    if not params:
        return ""
    rows = []
    for p in params:
        schema = p.get("schema") or {}
        kind = schema.get("type") or ", ".join(
            str(s.get("type")) for s in schema.get("anyOf", []) if s.get("type")) or ""
        rows.append(
            f"<tr><td><code>{_e(p.get('name', ''))}</code></td><td>{_e(p.get('in', ''))}</td>"
            f"<td>{'yes' if p.get('required') else ''}</td><td>{_e(kind)}</td>"
            f"<td class=\"d\">{_e(p.get('description') or schema.get('description') or '')}"
            "</td></tr>"
        )
    return ("<table><tr><th>parameter</th><th>in</th><th>required</th><th>type</th>"
            "<th>meaning</th></tr>" + "".join(rows) + "</table>")


def api_reference_html(spec: dict) -> str:
    """The whole page for the OpenAPI document ``spec`` (every text escaped)."""
    info = spec.get("info") or {}
    parts = [
        "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">",
        f"<title>{_e(info.get('title', 'API'))} API</title><style>{_STYLE}</style></head><body>",
        f"<h1>{_e(info.get('title', ''))} API <span class=\"muted\">"
        f"{_e(info.get('version', ''))}</span></h1>",
        f"<p>{_e(info.get('description', ''))}</p>",
        "<p class=\"muted\">Every route and its parameters; the bodies' schemas (the study, "
        "<code>StudyDoc</code>, with its catalogue ids, models and grid axes) are in "
        "<a href=\"/openapi.json\">/openapi.json</a>. <a href=\"/\">studies</a></p>",
    ]
    for path, ops in (spec.get("paths") or {}).items():
        for method, op in ops.items():
            if not isinstance(op, dict):
                continue
            parts.append(f"<h2><span class=\"m\">{_e(method.upper())}</span>{_e(path)}</h2>")
            if op.get("summary"):
                parts.append(f"<p>{_e(op['summary'])}</p>")
            if op.get("description"):
                parts.append(f"<p class=\"muted\">{_e(op['description'])}</p>")
            parts.append(_parameters(op.get("parameters") or []))
            body = (op.get("requestBody") or {}).get("content") or {}
            if body:
                parts.append("<p>body: " + ", ".join(f"<code>{_e(t)}</code>" for t in body)
                             + "</p>")
    parts.append("</body></html>")
    return "".join(parts)
