#!/usr/bin/env python3
"""The run registry and the variants (hideseek_analysis.registry): src/hideseek_analysis/scripts/hideseek_registry.py --help."""
import os
import signal
import sys

# In a checkout the package lies beside this folder; in an install space it is on the Python path.
PACKAGE = os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "python")
if os.path.isdir(PACKAGE):
    sys.path.insert(0, PACKAGE)
from hideseek_analysis import registry  # noqa: E402

if __name__ == "__main__":
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # `... runs | head` ends quietly, as a shell tool does
    sys.exit(registry.main())
