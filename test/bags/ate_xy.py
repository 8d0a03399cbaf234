#!/usr/bin/python3
"""ATE xy RMSE (m) of a TUM trajectory against the truth, the truth interpolated linearly at each
estimate's time; estimates outside the truth's span are left out. Prints: RMSE MATCHED.

Usage: ate_xy.py TRUTH.tum ESTIMATE.tum
"""
import bisect
import math
import sys


def read_tum(path):
    poses = []
    with open(path) as f:
        for line in f:
            if line.strip() and not line.startswith("#"):
                t, x, y = (float(v) for v in line.split()[:3])
                poses.append((t, x, y))
    return poses


def main():
    truth = read_tum(sys.argv[1])
    times = [p[0] for p in truth]
    squares = []
    for t, x, y in read_tum(sys.argv[2]):
        i = bisect.bisect_left(times, t)
        if i == 0 or i == len(times):
            continue
        (t0, x0, y0), (t1, x1, y1) = truth[i - 1], truth[i]
        a = (t - t0) / (t1 - t0)
        squares.append((x - (x0 + a * (x1 - x0))) ** 2 + (y - (y0 + a * (y1 - y0))) ** 2)
    if not squares:
        print("nan 0")
        return 1
    print(f"{math.sqrt(sum(squares) / len(squares)):.6f} {len(squares)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
