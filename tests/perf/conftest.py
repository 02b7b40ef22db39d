"""The performance tests share the benchmarks' synthetic problems (benchmarks/testproblems.py, not part
of the package): that folder on the import path."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
