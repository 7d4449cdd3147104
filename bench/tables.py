#!/usr/bin/env python3
"""Prints the markdown tables of docs/performance.md from the JSON that
wavepath_bench_bvh --json writes. Python 3 standard library only.

Usage: python3 bench/tables.py bvh.json
"""

import json
import sys


def main():
    results = json.load(open(sys.argv[1]))

    print("Build (best of 3 a run below 2x10^6 triangles, else 1) and the scene's memory")
    print()
    print("| triangles | wavepath BVH ms | wavepath flatten ms | Embree medium ms "
          "| Embree high ms | wavepath / Embree medium | wavepath / Embree high "
          "| wavepath B/tri | Embree medium B/tri | Embree high B/tri | max RSS MiB |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in results:
        b, m = r["build"], r["memory"]
        ms = lambda key: (f"{1e3 * b[key]:.4f}" if b[key] < 1e-2 else f"{1e3 * b[key]:,.0f}")
        ratio = lambda key: (f"{b['wavepath_bvh_s'] / b[key]:.2f}" if b[key] > 0 else "-")
        print(f"| {r['triangles']:,} | {ms('wavepath_bvh_s')} | {ms('wavepath_flatten_s')} "
              f"| {ms('embree_medium_s')} | {ms('embree_high_s')} | {ratio('embree_medium_s')} "
              f"| {ratio('embree_high_s')} | {m['wavepath_bytes_per_triangle']:.1f} "
              f"| {m['embree_medium_bytes_per_triangle']:.1f} "
              f"| {m['embree_high_bytes_per_triangle']:.1f} | {r['max_rss_mib']} |")
    print()

    print("Throughput, Mrays/s (best of 3 a run; Embree on its high-quality BVH, medium in brackets)")
    print()
    print("| triangles | kind | rays | count | wavepath | Embree 1-ray | Embree 16-ray "
          "| wavepath / Embree 16 | hits checked (same / tie / differ) | load at start, by run |")
    print("|---:|---|---|---:|---:|---:|---:|---:|---|---|")
    for r in results:
        for t in r["traced"]:
            c = t["check_vs_embree_medium_1"]
            differ = c["t_differs"] + c["other"] + c["hit_miss"]
            print(f"| {r['triangles']:,} | {t['kind']} | {t['rays']} | {t['count']:,} "
                  f"| {t['wavepath_mrays']:.2f} "
                  f"| {t['embree_high_1_mrays']:.2f} ({t['embree_medium_1_mrays']:.2f}) "
                  f"| {t['embree_high_16_mrays']:.2f} ({t['embree_medium_16_mrays']:.2f}) "
                  f"| {t['wavepath_mrays'] / t['embree_high_16_mrays']:.2f} "
                  f"| {c['same']:,} / {c['tie']:,} / {differ:,} "
                  f"| {r['load_start']} |")


if __name__ == "__main__":
    main()
