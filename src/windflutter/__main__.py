import sys

from windflutter.cli import main

sys.exit(main())
