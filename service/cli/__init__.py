"""Command line entry point (placeholder while the package is assembled)."""


def main() -> None:  # pragma: no cover
    raise SystemExit("beltstudy: not built yet")
