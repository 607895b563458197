from rtfarm.cli import main

raise SystemExit(main())
