#!/usr/bin/env python3
"""Table 2 with 95 % intervals, of the sweep's runs or of the shipped policies (hideseek_analysis.table2)."""
import os
import sys

# In a checkout the package lies beside this folder; in an install space it is on the Python path.
PACKAGE = os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "python")
if os.path.isdir(PACKAGE):
    sys.path.insert(0, PACKAGE)
from hideseek_analysis import table2  # noqa: E402

if __name__ == "__main__":
    sys.exit(table2.main())
