import sys

from beltstudy.service.cli import main

sys.exit(main())
