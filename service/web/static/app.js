// beltstudy pages: fetch the JSON API with the session's bearer token and fill the page.
// Data goes into the page through textContent and DOM properties only, never as markup.
"use strict";

const TOKEN_KEY = "beltstudy.token";
const ACTIVE = ["queued", "running"];

function token() { return sessionStorage.getItem(TOKEN_KEY) || ""; }

function authHeaders(extra) {
  const headers = Object.assign({}, extra || {});
  const t = token();
  if (t) headers["Authorization"] = "Bearer " + t;
  return headers;
}

class ApiError extends Error {
  constructor(status, message) { super(message); this.status = status; }
}

async function request(path, options) {
  const opts = Object.assign({}, options || {});
  opts.headers = authHeaders(opts.headers);
  const res = await fetch(path, opts);
  if (!res.ok) {
    let message = res.status + " " + res.statusText;
    try {
      const body = await res.json();
      if (body && body.message) message = body.message;
    } catch (e) { /* not JSON */ }
    if (res.status === 401) message += " (enter the service token above)";
    throw new ApiError(res.status, message);
  }
  return res;
}

async function api(path, options) { return (await request(path, options)).json(); }

function el(tag, props, children) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(props || {})) {
    if (k === "text") node.textContent = v == null ? "" : String(v);
    else if (k === "class") node.className = v;
    else if (k === "data") Object.assign(node.dataset, v);
    else node[k] = v;
  }
  for (const child of children || []) node.append(child);
  return node;
}

function showError(message) {
  const box = document.getElementById("error");
  box.textContent = message || "";
  box.hidden = !message;
}

function fmtSeconds(s) {
  if (s == null) return "–";
  s = Number(s);
  if (s < 60) return s.toFixed(1) + " s";
  if (s < 3600) return Math.floor(s / 60) + " min " + Math.round(s % 60) + " s";
  return Math.floor(s / 3600) + " h " + Math.round((s % 3600) / 60) + " min";
}

// Numbers as service/web/numbers.py writes them: four significant digits but never fewer than
// the integer part has, thousands grouped by a narrow no-break space, no exponent
// (16 886, not 1.689e+4); below 1e-4 as 1.2 × 10⁻⁵.
function fmtNumber(x, digits = 4) {
  if (!Number.isFinite(x)) return "–";
  if (x === 0) return "0";
  const sign = x < 0 ? "-" : "";
  const a = Math.abs(x);
  if (a < 1e-4) {
    const e = Math.floor(Math.log10(a));
    const m = (a / 10 ** e).toFixed(digits - 1).replace(/\.?0+$/, "");
    const sup = String(e).replace(/[-0-9]/g, (c) => "⁻⁰¹²³⁴⁵⁶⁷⁸⁹"["-0123456789".indexOf(c)]);
    return sign + m + " × 10" + sup;
  }
  const decimals = Math.max(digits - 1 - Math.floor(Math.log10(a)), 0);
  const [whole, frac = ""] = a.toFixed(decimals).split(".");
  const kept = frac.replace(/0+$/, "");
  return sign + whole.replace(/\B(?=(\d{3})+(?!\d))/g, "\u202f") + (kept ? "." + kept : "");
}

function fmtValue(v) {
  if (v == null) return "";
  if (typeof v === "number") return fmtNumber(v);
  return String(v);
}

// The unit a column's name ends in (SPEC: every key that carries a unit ends in it), longest
// suffix first; none for a name without one.
const UNITS = [["_kn_m", "kN/m"], ["_kg_m2", "kg\u00b7m\u00b2"], ["_kg_m", "kg/m"],
  ["_knm", "kN\u00b7m"], ["_m_s", "m/s"], ["_rad_s", "rad/s"], ["_t_h", "t/h"],
  ["_kn", "kN"], ["_kw", "kW"], ["_kg", "kg"], ["_pct", "%"], ["_deg", "\u00b0"],
  ["_c", "\u00b0C"], ["_mm", "mm"], ["_m", "m"], ["_s", "s"], ["_h", "h"], ["_n", "N"]];

function unitOf(column) {
  const hit = UNITS.find(([suffix]) => column.endsWith(suffix));
  return hit ? hit[1] : "";
}

// A cell of column ``column``: a number in engineering format with its column's unit (a
// no-break space between), anything else as text.
function fmtCell(column, v) {
  if (typeof v !== "number") return fmtValue(v);
  const unit = unitOf(column);
  return fmtNumber(v) + (unit ? "\u00a0" + unit : "");
}

// A message cell that keeps its row short: the first 90 characters, the rest folded into a
// <details> element (text nodes only).
function messageCell(text) {
  const s = text == null ? "" : String(text);
  if (s.length <= 90) return el("td", { text: s, class: "message" });
  let cut = s.lastIndexOf(" ", 90);
  if (cut < 45) cut = 90;
  return el("td", { class: "message" }, [el("details", {}, [
    el("summary", { text: s.slice(0, cut) + " …" }), s.slice(cut)])]);
}

// The clauses of a run's message, joined by "; " (service/web/verdicts.py said_clauses): a "; "
// inside parentheses belongs to its clause, so "(takeup.travel_m; from -0.3 to 4.2 m ...)"
// stays on one line.
function clauses(message) {
  const s = message == null ? "" : String(message);
  const parts = [];
  let depth = 0, start = 0;
  for (let k = 0; k < s.length; k++) {
    const ch = s[k];
    if (ch === "(") depth += 1;
    else if (ch === ")") depth -= 1;
    else if (depth <= 0 && ch === ";" && s[k + 1] === " ") {
      parts.push(s.slice(start, k));
      start = k + 2;
    }
  }
  parts.push(s.slice(start));
  // a clause saying what would avoid a finding joins the finding before it (a warning cuts
  // the two with "; " as the message cuts warnings), as the report does (verdicts.py
  // said_clauses): a slip and the take-up that avoids it are one item
  const out = [];
  for (const c of parts.filter((p) => p.trim())) {
    const last = out.length ? out[out.length - 1] : null;
    const opens = c.startsWith("note: ") || c.startsWith("marginal: ");
    if (last !== null && c.includes("would avoid") && !last.includes("would avoid") && !opens) {
      out[out.length - 1] = last + "; " + c;
    } else {
      out.push(c);
    }
  }
  return out;
}

function setProgress(bar, st) {
  bar.max = Math.max(st.total || 0, 1);
  bar.value = st.done || 0;
  bar.dataset.done = st.done;
  bar.dataset.total = st.total;
  bar.dataset.state = st.state;
}

// Images: fetched with the token, shown from an object URL; the content type and size are
// kept on the element (data-type, data-bytes) and data-loaded is set once it is drawn.
async function loadImage(img) {
  img.dataset.loaded = "";
  try {
    const res = await request(img.dataset.src);
    const blob = await res.blob();
    const old = img.dataset.url;
    const url = URL.createObjectURL(blob);
    img.onload = () => { img.dataset.loaded = "1"; if (old) URL.revokeObjectURL(old); };
    img.onerror = () => { img.dataset.loaded = "error"; };
    img.dataset.type = res.headers.get("content-type") || "";
    img.dataset.bytes = String(blob.size);
    img.dataset.url = url;
    img.src = url;
  } catch (e) {
    img.dataset.loaded = "error";
    img.alt = "plot failed: " + e.message;
    showError(e.message);
  }
}

function loadImages() { document.querySelectorAll("img.plot").forEach(loadImage); }

// Downloads: plain links without a token; with a token, fetched and saved from a blob.
function wireDownloads() {
  document.querySelectorAll("a.download").forEach((a) => {
    a.addEventListener("click", async (ev) => {
      if (!token()) return;
      ev.preventDefault();
      try {
        const blob = await (await request(a.href)).blob();
        const url = URL.createObjectURL(blob);
        const tmp = el("a", { href: url, download: a.getAttribute("download") || "" });
        document.body.append(tmp);
        tmp.click();
        tmp.remove();
        setTimeout(() => URL.revokeObjectURL(url), 10000);
      } catch (e) { showError(e.message); }
    });
  });
}

function wireLogin(onChange) {
  const form = document.getElementById("login");
  const input = document.getElementById("token-input");
  const state = document.getElementById("token-state");
  const show = () => { state.textContent = token() ? "token set for this session" : ""; };
  form.addEventListener("submit", (ev) => {
    ev.preventDefault();
    sessionStorage.setItem(TOKEN_KEY, input.value.trim());
    input.value = "";
    show();
    showError("");
    onChange();
  });
  document.getElementById("token-clear").addEventListener("click", () => {
    sessionStorage.removeItem(TOKEN_KEY);
    show();
    onChange();
  });
  show();
}

async function cancelStudy(id, name) {
  if (!window.confirm("Cancel study '" + name + "' and delete its results?")) return false;
  await api("/studies/" + encodeURIComponent(id), { method: "DELETE" });
  return true;
}

// ---------------------------------------------------------------------------- study list
function indexPage() {
  let timer = null;
  const tbody = document.querySelector("#studies tbody");

  function row(st) {
    const link = el("a", { href: "/ui/studies/" + encodeURIComponent(st.id), text: st.name });
    const bar = el("progress", { class: "progress" });
    setProgress(bar, st);
    const cancel = el("button", { type: "button", class: "danger",
      text: ACTIVE.includes(st.state) ? "cancel" : "delete" });
    cancel.addEventListener("click", async () => {
      try { if (await cancelStudy(st.id, st.name)) refresh(); } catch (e) { showError(e.message); }
    });
    return el("tr", { data: { id: st.id, state: st.state } }, [
      el("td", {}, [link]),
      el("td", { class: "state state-" + st.state, text: st.state }),
      el("td", {}, [bar]),
      el("td", { class: "counts", text: st.done + " / " + st.failed + " / " + st.total }),
      el("td", { text: fmtSeconds(st.elapsed_s) }),
      el("td", { text: ACTIVE.includes(st.state) ? fmtSeconds(st.eta_s) : "–" }),
      el("td", {}, [cancel]),
    ]);
  }

  async function refresh() {
    clearTimeout(timer);
    let active = false;
    try {
      const data = await api("/studies");
      tbody.replaceChildren(...data.studies.slice().reverse().map(row));
      document.getElementById("studies-empty").hidden = data.studies.length > 0;
      active = data.studies.some((s) => ACTIVE.includes(s.state));
      showError("");
    } catch (e) { showError(e.message); }
    timer = setTimeout(refresh, active ? 1000 : 5000);
  }

  const text = document.getElementById("study-text");
  document.getElementById("study-file").addEventListener("change", async (ev) => {
    const file = ev.target.files[0];
    if (file) text.value = await file.text();
  });
  document.getElementById("submit-form").addEventListener("submit", async (ev) => {
    ev.preventDefault();
    const errorBox = document.getElementById("submit-error");
    const result = document.getElementById("submit-result");
    errorBox.hidden = true;
    result.hidden = true;
    const body = text.value;
    const isJson = body.trim().startsWith("{");
    try {
      const st = await api("/studies", {
        method: "POST", body,
        headers: { "Content-Type": isJson ? "application/json" : "application/yaml" },
      });
      result.replaceChildren("Submitted ",
        el("a", { href: "/ui/studies/" + encodeURIComponent(st.id), text: st.name }),
        " (" + st.total + (st.total === 1 ? " run, " : " runs, ") + st.state + ")");
      result.hidden = false;
      refresh();
    } catch (e) {
      errorBox.textContent = e.message;
      errorBox.hidden = false;
    }
  });
  wireLogin(refresh);
  refresh();
}

// ---------------------------------------------------------------------------- study page
// The steady running slip margin alone hides a drive that slips at breakaway or in the
// transient: the start's margin and the transient's lowest sit beside it.
const RESULT_COLUMNS = ["status", "power_kw", "te_kn", "t_max_kn", "safety_factor",
  "slip_margin", "slip_margin_start", "sag_max_pct", "t_max_dyn_kn", "dyn_factor",
  "slip_margin_min_dyn", "stop_time_s", "takeup_mass_kg", "fill_pct", "message"];
// the transient's columns, left out of a steady-only study's table (every cell empty there)
const DYNAMIC_COLUMNS = ["t_max_dyn_kn", "dyn_factor", "slip_margin_min_dyn", "stop_time_s"];

// The design basis as table rows: one per auto size of each conveyor design.
// a size's constraint with its case, as the runs' *_governed_by columns state it (SPEC 7.2)
const governedAt = (why, at) => (at && why !== "given" ? why + " @ " + at : why);

function designRows(designs) {
  const rows = [];
  const fmt = (v) => fmtValue(v);
  for (const d of designs) {
    const where = Object.entries(d.axes).map(([k, v]) => k + "=" + v).join(", ") || "the conveyor";
    const s = d.sizes;
    if (s.takeup) {
      rows.push([where, "take-up " + (s.takeup.unit === "kg" ? "mass" : "pretension"),
        fmt(s.takeup.value) + " " + s.takeup.unit, governedAt(s.takeup.governed_by, s.takeup.at),
        s.takeup.case]);
    }
    (s.drives || []).forEach((dr, i) => {
      if (dr) rows.push([where, "rated power, drive " + (i + 1), fmt(dr.rated_power_kw) + " kW",
        governedAt(dr.governed_by, dr.at), dr.case]);
    });
    if (s.brakes) {
      const sum = (e) => e.force_kn.reduce((a, b) => a + b, 0);
      const reasons = (e) => [...new Set(e.governed_by.map((g) => governedAt(g, e.at)))].join("+");
      rows.push([where, "brake force, held at rest", fmt(sum(s.brakes.holding)) + " kN",
        reasons(s.brakes.holding), s.brakes.holding.case]);
      for (const [t, e] of Object.entries(s.brakes.stop_time_s)) {
        rows.push([where, "brake force, brake stop in " + t + " s", fmt(sum(e)) + " kN",
          reasons(e), e.case]);
      }
    }
  }
  return rows;
}

// Rows per page of the runs table, and the choices offered. A page of the table's columns
// is about 0.5 kB a row as JSON and answers in about 50 ms up to a few hundred rows on a
// 20 000-run study (BENCHMARKS.md, section 4b): the page never asks for every row.
const PAGE_SIZE = 100;
const PAGE_SIZES = [50, 100, 200, 500];

function studyPage(id) {
  let timer = null;
  let axes = [];
  let models = [];
  let stored = [];  // the columns of the study's runs table
  let sort = { column: null, dir: 1 };
  let filters = {};
  let offset = 0;
  let limit = PAGE_SIZE;
  let total = 0;
  let done = 0;
  let asked = 0;  // the number of the last runs request: older answers are dropped
  let warned = null;  // finished runs with status warning
  let dynamics = true;  // a steady-only study's table leaves out the transient's columns
  let plotsShown = false;
  let lastDone = -1;

  function columns() {
    const cols = axes.map((a) => a.column);
    if (!cols.includes("friction_model")) cols.push("friction_model");
    return cols.concat(RESULT_COLUMNS.filter((c) => dynamics || !DYNAMIC_COLUMNS.includes(c)));
  }

  function buildFilters() {
    const box = document.getElementById("filters");
    const items = axes.map((a) => ({ column: a.column, values: a.values }));
    if (!axes.some((a) => a.column === "friction_model")) {
      items.push({ column: "friction_model", values: models });
    }
    items.push({ column: "status", values: ["ok", "warning", "failed"] });
    box.replaceChildren(...items.map((item) => {
      const select = el("select", { name: item.column, data: { column: item.column } },
        [el("option", { value: "", text: "all" })].concat(
          item.values.map((v) => el("option", { value: String(v), text: String(v) }))));
      select.addEventListener("change", () => {
        filters[item.column] = select.value;
        offset = 0;
        loadRuns().catch((e) => showError(e.message));
      });
      return el("label", { class: "filter" }, [item.column + " ", select]);
    }));
  }

  // The query of one page: the table's columns the study has, the filters, the order.
  function runsQuery() {
    const q = new URLSearchParams({ format: "json", limit: String(limit), offset: String(offset) });
    const cols = ["run_id"].concat(columns()).filter((c, i, all) =>
      stored.includes(c) && all.indexOf(c) === i);
    q.set("columns", cols.join(","));
    if (sort.column) q.set("sort", (sort.dir < 0 ? "-" : "") + sort.column);
    for (const [c, v] of Object.entries(filters)) {
      if (v === "") continue;
      if (c === "status") q.set("status", v);
      else q.append("filter", c + "=" + v);
    }
    return q;
  }

  function renderHead() {
    const head = document.querySelector("#runs thead tr");
    head.replaceChildren(...columns().map((c) => {
      const th = el("th", { text: c + (sort.column === c ? (sort.dir > 0 ? " ▲" : " ▼") : ""),
        data: { column: c }, title: stored.includes(c) ? "sort by " + c : "" });
      if (stored.includes(c)) {
        th.addEventListener("click", () => {
          sort = { column: c, dir: sort.column === c ? -sort.dir : 1 };
          offset = 0;
          loadRuns().catch((e) => showError(e.message));
        });
      }
      return th;
    }), el("th", { text: "" }));
  }

  function renderRuns(rows) {
    const cols = columns();
    renderHead();
    const tbody = document.querySelector("#runs tbody");
    tbody.replaceChildren(...rows.map((r) => el("tr",
      { class: "status-" + r.status, data: { runId: r.run_id } },
      cols.map((c) => c === "message" ? messageCell(r[c]) : el("td", { text: fmtCell(c, r[c]) }))
        .concat([el("td", {}, [el("a", { text: "open",
          href: "/ui/studies/" + encodeURIComponent(id) + "/runs/" + encodeURIComponent(r.run_id) })])]))));
    const filtered = Object.values(filters).some((v) => v !== "");
    const count = document.getElementById("runs-count");
    count.dataset.total = String(total);
    count.dataset.done = String(done);
    const runs = (n) => fmtNumber(n) + (n === 1 ? " run" : " runs");
    count.textContent = "(" + (filtered ? fmtNumber(total) + " of " + runs(done) +
      (total === 1 ? " matches" : " match") + " the filters" : runs(total)) + ")";
    document.getElementById("runs-page").textContent = rows.length
      ? "rows " + fmtNumber(offset + 1) + "–" + fmtNumber(offset + rows.length) + " of " +
        fmtNumber(total)
      : (total ? "no rows past row " + fmtNumber(total) : "no rows");
    document.getElementById("runs-prev").disabled = offset <= 0;
    document.getElementById("runs-next").disabled = offset + rows.length >= total;
  }

  async function loadRuns() {
    const n = ++asked;
    const data = await api("/studies/" + encodeURIComponent(id) + "/runs?" + runsQuery());
    if (n !== asked) return;  // a newer page was asked for meanwhile
    total = data.total;
    if (offset > 0 && offset >= total) {  // fewer rows than before: the last page there is
      offset = Math.max(Math.floor((total - 1) / limit) * limit, 0);
      await loadRuns();
      return;
    }
    if (!document.querySelector("#filters select")) buildFilters();
    renderRuns(data.runs);
  }

  function wirePager() {
    const go = (to) => { offset = Math.max(to, 0); loadRuns().catch((e) => showError(e.message)); };
    document.getElementById("runs-prev").addEventListener("click", () => go(offset - limit));
    document.getElementById("runs-next").addEventListener("click", () => go(offset + limit));
    const size = document.getElementById("runs-limit");
    size.replaceChildren(...PAGE_SIZES.map((k) => el("option",
      { value: String(k), text: String(k), selected: k === PAGE_SIZE })));
    size.addEventListener("change", () => { limit = Number(size.value); go(0); });
  }

  async function loadInfo() {
    const info = await api("/ui/data/studies/" + encodeURIComponent(id));
    axes = info.axes;
    models = info.models || [];
    stored = info.columns || [];
    document.title = "beltstudy · " + info.name;
    document.getElementById("study-name").textContent = info.name;
    document.getElementById("conveyor-name").textContent = info.conveyor_name;
    document.getElementById("conveyor-source").textContent =
      info.conveyor_source ? "(" + info.conveyor_source + ")" : "";
    document.getElementById("dynamics").textContent = info.dynamics ? "on" : "off";
    dynamics = Boolean(info.dynamics);
    document.getElementById("description").textContent = info.description;
    document.getElementById("axes").replaceChildren(...axes.flatMap((a) => [
      el("dt", { text: a.name }), el("dd", { text: a.values.map(String).join(", ") +
        (a.group == null ? "" : "  (zip group " + (a.group + 1) + ")") })]));
    const merged = document.getElementById("merged");
    const inert = info.merged_axes || [];
    merged.textContent = info.merged ? info.merged + " of " + info.grid_points +
      " grid points merged into identical runs (" + (inert.length ? inert.join(", ") +
        (inert.length === 1 ? " changes" : " change") + " no run of this study" :
        "an axis that does not change them") + ")" : "";
    merged.hidden = !info.merged;
    const rows = designRows(info.designs || []);
    // how the auto sizes were found: said only when there are any (the table says when not)
    const designCase = document.getElementById("design-case");
    designCase.textContent = !rows.length ? "" : info.design
      ? "Auto sizes computed at the design case " + Object.entries(info.design)
        .map(([k, v]) => k + " " + v).join(", ") + " and held for every run of a conveyor design."
      : "Auto sizes: the largest requirement over the study's models and temperatures at full " +
        "load, computed once per conveyor design and held for every run of it.";
    designCase.hidden = !rows.length;
    document.querySelector("#designs tbody").replaceChildren(...(rows.length ? rows.map((r) =>
      el("tr", {}, r.map((c) => el("td", { text: c })))) : [el("tr", {}, [el("td", {
        text: "no auto sizes: every size is given in the conveyor file", colSpan: 5 })])]));
  }

  async function poll() {
    clearTimeout(timer);
    let active = false;
    try {
      const st = await api("/studies/" + encodeURIComponent(id));
      active = ACTIVE.includes(st.state);
      const state = document.getElementById("state");
      state.textContent = st.state;
      state.className = "state state-" + st.state;
      setProgress(document.getElementById("progress"), st);
      document.getElementById("counts").textContent =
        st.done + " of " + st.total + " done, " + st.failed + " failed" +
        (warned == null ? "" : ", " + warned + " with warnings");
      done = st.done;
      document.getElementById("elapsed").textContent = fmtSeconds(st.elapsed_s);
      document.getElementById("eta").textContent = active ? fmtSeconds(st.eta_s) : "–";
      const msg = document.getElementById("study-message");
      msg.textContent = st.message || "";
      msg.hidden = !st.message;
      if (st.done !== lastDone) {
        lastDone = st.done;
        await loadRuns();
        // "0 failed" alone reads as all well: say how many finished runs carry warnings
        // (a belt that ran away or did not stop is a warning, not a failure)
        warned = (await api("/studies/" + encodeURIComponent(id) +
          "/runs?status=warning&limit=1&columns=run_id")).total;
        document.getElementById("counts").textContent =
          st.done + " of " + st.total + " done, " + st.failed + " failed, " + warned +
          " with warnings";
      }
      if (!active && !plotsShown) { plotsShown = true; loadImages(); }
      showError("");
    } catch (e) { showError(e.message); }
    if (active) timer = setTimeout(poll, 1000);
  }

  async function start() {
    try { await loadInfo(); } catch (e) {
      showError(e.message);
      // a deleted (or never stored) study: its sections would draw broken plots and links
      if (e.status === 404) {
        document.querySelectorAll("main section, main .status, main .meta, main h1 ~ p")
          .forEach((n) => { n.hidden = true; });
      }
      return;
    }
    lastDone = -1;
    plotsShown = false;
    poll();
  }

  document.getElementById("cancel").addEventListener("click", async () => {
    try {
      if (await cancelStudy(id, document.getElementById("study-name").textContent)) {
        window.location.href = "/";
      }
    } catch (e) { showError(e.message); }
  });
  wireDownloads();
  wirePager();
  wireLogin(start);
  start();
}

// ---------------------------------------------------------------------------- run page
const HIDDEN_FIELDS = ["study_id", "run_id", "status", "message", "te_components_kn"];

function runPage(studyId, runId) {
  async function start() {
    try {
      const info = await api("/ui/data/studies/" + encodeURIComponent(studyId));
      document.getElementById("run-study").textContent = "of " + info.name;
      document.title = "beltstudy · " + info.name + " · " + runId;
      const detail = await api("/studies/" + encodeURIComponent(studyId) + "/runs/" +
        encodeURIComponent(runId));
      const s = detail.summary;
      const axisCols = info.axes.map((a) => a.column);
      if (!axisCols.includes("friction_model")) axisCols.push("friction_model");
      document.getElementById("run-axes").replaceChildren(...axisCols.flatMap((c) => [
        el("dt", { text: c }), el("dd", { text: s[c] == null
          ? "any (grid points that differ only here are this one run)" : fmtValue(s[c]) })]));
      const status = document.getElementById("run-status");
      status.textContent = s.status;
      status.className = "state status-" + s.status;
      const warnings = clauses(s.message);
      document.getElementById("run-warnings").replaceChildren(
        ...warnings.map((m) => el("li", { text: m })));
      const rows = Object.entries(s).filter(([k, v]) => !HIDDEN_FIELDS.includes(k) &&
        !axisCols.includes(k) && v != null);
      for (const [part, v] of Object.entries(s.te_components_kn || {})) {
        if (v != null) rows.push(["te_components_kn." + part, v]);
      }
      // a sampled run's error bars (accuracy: {sample: ...}): "value ± bar" beside each figure
      const bars = detail.accuracy || {};
      const withBar = (k, v) => typeof bars[k + "_err"] === "number"
        ? fmtCell(k, v) + " ± " + fmtCell(k, bars[k + "_err"]) : fmtCell(k, v);
      if (detail.accuracy) {
        rows.unshift(["error bars (meshes; method of each figure)",
          (bars.accuracy_elements || "") + "; " + (bars.accuracy_methods || "")]);
      }
      document.querySelector("#run-summary tbody").replaceChildren(...rows.map(([k, v]) =>
        el("tr", {}, [el("th", { text: k }), el("td", { text: withBar(k, v) })])));
      loadImages();
      showError("");
    } catch (e) { showError(e.message); }
  }
  wireLogin(start);
  start();
}

document.addEventListener("DOMContentLoaded", () => {
  const body = document.body.dataset;
  if (body.page === "index") indexPage();
  else if (body.page === "study") studyPage(body.studyId);
  else if (body.page === "run") runPage(body.studyId, body.runId);
});
