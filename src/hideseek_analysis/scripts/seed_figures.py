#!/usr/bin/env python3
"""The paper's Figures 4-7, Table 3, the behaviour table and the t-SNE across training seeds (hideseek_analysis.figures)."""
import os
import sys

# In a checkout the package lies beside this folder; in an install space it is on the Python path.
PACKAGE = os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "python")
if os.path.isdir(PACKAGE):
    sys.path.insert(0, PACKAGE)
from hideseek_analysis import figures  # noqa: E402

if __name__ == "__main__":
    sys.exit(figures.main())
