import sys

from hideseek_pipeline.cli import main

sys.exit(main())
