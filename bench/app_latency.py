"""Slider change → updated plot, in a real browser, median and 95th percentile."""

from __future__ import annotations

import json
import sys

import numpy as np

from bench.browser import browser, measure_latency, open_app, running_server


def bench_app_latency(changes: int = 24) -> dict:
    with running_server() as url, browser() as b:
        page = open_app(b, url)
        lat = measure_latency(page, changes=changes)
    lat = np.array(lat[2:])  # the first changes also warm the figure code paths
    return {"app_latency_median_ms": float(np.median(lat)), "app_latency_p95_ms": float(np.percentile(lat, 95)),
            "app_latency_changes": int(len(lat))}


if __name__ == "__main__":
    res = bench_app_latency()
    print(json.dumps(res, indent=2))
    if len(sys.argv) > 1:
        with open(sys.argv[1], "w") as fh:
            json.dump(res, fh, indent=2)
