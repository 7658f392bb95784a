#!/usr/bin/env python3
"""The paper's claims decided on the sweep's runs (hideseek_analysis.claims)."""
import os
import sys

# In a checkout the package lies beside this folder; in an install space it is on the Python path.
PACKAGE = os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "python")
if os.path.isdir(PACKAGE):
    sys.path.insert(0, PACKAGE)
from hideseek_analysis import claims  # noqa: E402

if __name__ == "__main__":
    sys.exit(claims.main())
