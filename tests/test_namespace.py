"""The installed import names live under one namespace: ``beltstudy.engine`` and
``beltstudy.service`` import from outside the checkout, ``engine`` and ``service`` do not, and
the ``beltstudy`` command runs (issue: a generic top-level ``engine`` or ``service`` would be
shadowed by any such file in the working directory and collide with other projects)."""

from __future__ import annotations

import subprocess
import sys

import pytest


def _python(code: str, cwd) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", code], cwd=cwd, capture_output=True,
                          text=True, timeout=120)


def test_namespaced_packages_import_from_outside_the_checkout(tmp_path):
    r = _python("import beltstudy.engine, beltstudy.service; print(beltstudy.engine.__version__)",
                tmp_path)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip()


@pytest.mark.parametrize("name", ["engine", "service"])
def test_generic_top_level_names_are_not_installed(tmp_path, name):
    r = _python(f"import {name}", tmp_path)
    assert r.returncode != 0
    assert f"No module named '{name}'" in r.stderr


def test_a_service_py_in_the_working_directory_does_not_shadow_the_package(tmp_path):
    (tmp_path / "service.py").write_text("raise SystemExit('shadowed')\n")
    (tmp_path / "engine.py").write_text("raise SystemExit('shadowed')\n")
    r = _python("import beltstudy.service.cli, beltstudy.engine.run; print('ok')", tmp_path)
    assert r.returncode == 0 and r.stdout.strip() == "ok", r.stderr


def test_the_command_runs(tmp_path):
    exe = subprocess.run([sys.executable, "-m", "beltstudy.service.cli", "--help"], cwd=tmp_path,
                         capture_output=True, text=True, timeout=120)
    assert exe.returncode == 0 and "usage: beltstudy" in exe.stdout
