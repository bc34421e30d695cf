"""Slider change → all visible plots updated, in a real browser: median and 95th percentile.

Run from the checkout: ``python -m bench.app_latency [out.json]``. Uses the browser helpers
of the test suite (tests/browser/helpers.py): Playwright driving Debian's chromium.
"""

from __future__ import annotations

import json
import os
import sys

import numpy as np

from tests.browser.helpers import browser, measure_latency, open_app, running_server


def bench_app_latency(changes: int = 42, width: int = 1600, height: int = 1000) -> dict:
    with running_server() as (url, _), browser() as b:
        page = open_app(b, url, width, height)
        lat = measure_latency(page, changes=changes)
    lat = np.array(lat[2:])  # the first changes also warm the figure code paths
    return {"app_latency_median_ms": float(np.median(lat)), "app_latency_p95_ms": float(np.percentile(lat, 95)),
            "app_latency_changes": int(len(lat)), "viewport": f"{width}x{height}",
            "load_average_1min": os.getloadavg()[0], "cpus": os.cpu_count()}


if __name__ == "__main__":
    res = bench_app_latency()
    print(json.dumps(res, indent=2))
    if len(sys.argv) > 1:
        with open(sys.argv[1], "w") as fh:
            json.dump(res, fh, indent=2)
