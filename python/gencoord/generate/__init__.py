# SPDX-License-Identifier: BSD-3-Clause
"""`generate`: one generation as timed stages, load -> check -> derive -> optimize -> emit
(stages.py), its command line (cli.py), the model-file loader (load.py), the limits on a run
(limits.py), the choice of dense or recursive dynamics (dynamics_paths.py) and failures as
one line each (failures.py)."""
