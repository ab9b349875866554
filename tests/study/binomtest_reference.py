#!/usr/bin/env python3
"""SciPy's two-sided exact binomial test (p = 0.5) for the tests of `foveal study stats`.

Usage: binomtest_reference.py K/N [K/N ...]; prints a JSON list of p-values."""
import json
import sys

from scipy.stats import binomtest

pairs = [tuple(int(x) for x in arg.split("/")) for arg in sys.argv[1:]]
json.dump([binomtest(k, n, 0.5, alternative="two-sided").pvalue for k, n in pairs], sys.stdout)
