#!/usr/bin/env python3
"""Largest per-frame difference between two runs' quality columns (repetition 0): the
device scorer's frames.csv against the CPU scorer's. Usage: compare-scorers.py A.csv B.csv"""
import csv
import sys

COLUMNS = ["psnr_db", "ssim", "ssim_luma", "flip_mean", "flip_q1", "flip_median", "flip_q3",
           "eci", "flicker_ratio", "crawl_valid_fraction"]


def rows(path):
    return [r for r in csv.DictReader(open(path)) if r["repeat"] == "0"]


def main(a_path, b_path):
    a, b = rows(a_path), rows(b_path)
    assert len(a) == len(b), "different frame counts"
    worst = {c: 0.0 for c in COLUMNS}
    for x, y in zip(a, b):
        assert (x["variant"], x["frame"]) == (y["variant"], y["frame"]), "frames out of step"
        for c in COLUMNS:
            if x[c] == y[c]:
                continue  # the same text: inf, empty (no pair) or the same digits
            worst[c] = max(worst[c], abs(float(x[c]) - float(y[c])))
    print(f"{len(a)} frames; largest differences: " + ", ".join(f"{c} {v:.2g}" for c, v in worst.items()))


if __name__ == "__main__":
    main(*sys.argv[1:3])
