#!/usr/bin/python3
"""Compares PNG images pairwise: python3 compare_images.py LIMIT A1 B1 [A2 B2 ...]

Prints each pair's RMSE over the colour channels (0-255) and exits 1 if any is over LIMIT or the sizes differ."""
import sys

import matplotlib.image
import numpy


def main(argv):
    limit, files = float(argv[1]), argv[2:]
    if len(files) < 2 or len(files) % 2:
        sys.exit("compare_images.py: give LIMIT and pairs of PNG files")
    worst = 0.0
    for a_path, b_path in zip(files[0::2], files[1::2]):
        a = matplotlib.image.imread(a_path)[..., :3].astype(numpy.float64) * 255.0
        b = matplotlib.image.imread(b_path)[..., :3].astype(numpy.float64) * 255.0
        if a.shape != b.shape:
            print(f"{a_path} is {a.shape[1]}x{a.shape[0]}, {b_path} {b.shape[1]}x{b.shape[0]}")
            return 1
        rmse = float(numpy.sqrt(((a - b) ** 2).mean()))
        worst = max(worst, rmse)
        print(f"{a_path} vs {b_path}: RMSE {rmse:.3f}")
    print(f"largest RMSE {worst:.3f}, limit {limit}")
    return 0 if worst <= limit else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
