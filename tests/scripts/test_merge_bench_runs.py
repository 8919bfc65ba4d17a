#!/usr/bin/env python3
"""scripts/merge_bench_runs.py against hand-computed medians of three synthetic runs, and its
refusals (a benchmark missing from one run, a file that is not benchmark output)."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts",
                      "merge_bench_runs.py")


def entry(name, aggregate, real, live, run_type="aggregate"):
    return {"name": f"{name}_{aggregate}", "run_name": name, "run_type": run_type,
            "aggregate_name": aggregate, "repetitions": 3, "threads": 1, "iterations": 10,
            "real_time": real, "cpu_time": real * 1.01, "time_unit": "ns", "live": live}


def run_doc(date, lookup_ns, frame_us):
    return {"context": {"date": date, "num_cpus": 2},
            "benchmarks": [entry("BM_Lookup/a/1000", "mean", lookup_ns + 50, 1000),
                           entry("BM_Lookup/a/1000", "median", lookup_ns, 1000),
                           entry("BM_Lookup/a/1000", "stddev", float("nan"), 0),
                           entry("BM_Frame/a/1000", "median", frame_us, 1004)]}


class MergeBenchRuns(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.paths = []
        for i, (lookup, frame) in enumerate([(300.0, 20.0), (500.0, 18.0), (290.0, 30.0)]):
            path = os.path.join(self.dir.name, f"run{i}.json")
            with open(path, "w", encoding="utf-8") as f:
                json.dump(run_doc(f"day{i}", lookup, frame), f)
            self.paths.append(path)
        self.out = os.path.join(self.dir.name, "merged.json")

    def tearDown(self):
        self.dir.cleanup()

    def merge(self, paths):
        return subprocess.run([sys.executable, SCRIPT, *paths, "--out", self.out],
                              capture_output=True, text=True)

    def test_medians_over_runs_of_each_runs_median(self):
        result = self.merge(self.paths)
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(self.out, encoding="utf-8") as f:
            doc = json.load(f)
        by_name = {b["run_name"]: b for b in doc["benchmarks"]}
        self.assertEqual(list(by_name), ["BM_Lookup/a/1000", "BM_Frame/a/1000"])
        lookup = by_name["BM_Lookup/a/1000"]
        self.assertEqual(lookup["aggregate_name"], "median")
        self.assertEqual(lookup["real_time"], 300.0)  # median of 300, 500, 290; not the means
        self.assertAlmostEqual(lookup["cpu_time"], 303.0)
        self.assertEqual(lookup["run_times"], [300.0, 500.0, 290.0])
        self.assertEqual(lookup["live"], 1000)
        self.assertEqual(by_name["BM_Frame/a/1000"]["real_time"], 20.0)
        self.assertEqual([r["date"] for r in doc["context"]["merged_runs"]],
                         ["day0", "day1", "day2"])

    def test_a_benchmark_missing_from_a_run_is_an_error_and_nothing_is_written(self):
        with open(self.paths[1], encoding="utf-8") as f:
            doc = json.load(f)
        doc["benchmarks"] = doc["benchmarks"][:3]
        with open(self.paths[1], "w", encoding="utf-8") as f:
            json.dump(doc, f)
        result = self.merge(self.paths)
        self.assertEqual(result.returncode, 2)
        self.assertIn("run1.json: benchmark BM_Frame/a/1000 is not in every run", result.stderr)
        self.assertEqual(result.stderr.count("\n"), 1)
        self.assertFalse(os.path.exists(self.out))

    def test_a_file_that_is_not_benchmark_output_is_named(self):
        with open(self.paths[2], "w", encoding="utf-8") as f:
            f.write("{\"context\": {}}")
        result = self.merge(self.paths)
        self.assertEqual(result.returncode, 2)
        self.assertTrue(result.stderr.startswith(self.paths[2] + ": not a Google Benchmark"))
        self.assertFalse(os.path.exists(self.out))


if __name__ == "__main__":
    unittest.main()
