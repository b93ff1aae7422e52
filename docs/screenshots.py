"""Screenshots of a real study for the README and docs/web.md (headless Chromium).

Run against a service that holds the study (``beltstudy serve``, then ``beltstudy submit
studies/overland-design.yaml --wait``)::

    .venv/bin/python docs/screenshots.py STUDY_ID [--url http://127.0.0.1:8000]

writes ``docs/img/web-studies.png`` (the study list), ``web-study.png`` (the study page),
``web-run.png`` (the run with the largest transient tension) and ``report.png`` (the top of the
design report). Needs Debian's ``chromium`` and ``chromium-driver`` and selenium (the test
extra).
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import httpx

IMG = Path(__file__).resolve().parent / "img"


def _driver():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for arg in ("--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                f"--user-data-dir={tempfile.mkdtemp(prefix='beltstudy-shots-')}",
                "--window-size=1280,1100"):
        options.add_argument(arg)
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)


def _wait(driver, condition, timeout: float = 60.0) -> None:
    t0 = time.monotonic()
    while not condition(driver):
        if time.monotonic() - t0 > timeout:
            raise TimeoutError("the page did not finish loading")
        time.sleep(0.2)


def _loaded(driver) -> bool:
    return driver.execute_script(
        "const imgs = Array.from(document.querySelectorAll('img'));"
        "return imgs.every(i => i.complete && i.naturalWidth > 0);")


def _shot(driver, name: str, max_height: int = 3000) -> None:
    driver.execute_script("window.scrollTo(0, 0)")
    height = driver.execute_script("return document.documentElement.scrollHeight")
    driver.set_window_size(1280, min(max(int(height) + 40, 800), max_height))
    time.sleep(0.3)
    IMG.mkdir(parents=True, exist_ok=True)
    driver.save_screenshot(str(IMG / name))
    driver.set_window_size(1280, 1100)
    print(f"wrote {IMG / name}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("study_id")
    parser.add_argument("--url", default="http://127.0.0.1:8000")
    args = parser.parse_args()
    base = args.url.rstrip("/")
    runs = httpx.get(f"{base}/studies/{args.study_id}/runs", timeout=60).json()["runs"]
    run = max(runs, key=lambda r: r.get("t_max_dyn_kn") or r.get("t_max_kn") or 0.0)
    driver = _driver()
    try:
        driver.get(base + "/")
        _wait(driver, lambda d: d.find_elements("css selector", "#studies tbody tr"))
        _shot(driver, "web-studies.png")
        driver.get(f"{base}/ui/studies/{args.study_id}")
        _wait(driver, lambda d: len(d.find_elements("css selector", "#runs tbody tr"))
              == len(runs) and _loaded(d))
        _shot(driver, "web-study.png")
        driver.get(f"{base}/ui/studies/{args.study_id}/runs/{run['run_id']}")
        _wait(driver, lambda d: d.find_element("id", "run-status").text and _loaded(d))
        _shot(driver, "web-run.png")
        driver.get(f"{base}/studies/{args.study_id}/report")
        _wait(driver, _loaded)
        _shot(driver, "report.png", max_height=2400)
    finally:
        driver.quit()


if __name__ == "__main__":
    main()
