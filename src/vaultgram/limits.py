"""Every bound vaultgram puts on its inputs to stay within what a machine can do, in one place (and
light to import: the command line reads them to check its options before loading any stage).

>>> SPACING_RANGE, MAX_FACES
((0.01, 0.05), 2000000)
"""

from __future__ import annotations

#: The documented useful range of the relative spacing (paper §3.1: "between 1% to 5%"); the command
#: line holds ``--spacing`` to it unless ``--any-spacing`` is given.
SPACING_RANGE = (0.01, 0.05)
#: Spacings outside ``(0, SPACING_MAX]`` are rejected.
SPACING_MAX = 0.2
#: Largest coordinate a plan may have: beyond, squared lengths and areas overflow (1e200) or keep no
#: digit of the plan's shape.
MAX_COORDINATE = 1e15
#: Largest distance of a plan from the origin, in diagonals of the plan: the stages work in a local
#: frame (:mod:`vaultgram.geometry.frames`), but the files are written in the plan's coordinates, and
#: double precision keeps about 16 digits: at 1e9 diagonals, 7 of them are left for the plan's shape.
MAX_OFFSET = 1e9
#: Default limit on the number of faces of a mesh (``--max-faces``, :mod:`vaultgram.meshing.guards`).
MAX_FACES = 2_000_000
#: Peak memory of the whole pipeline (``vaultgram design``) per mesh face, in bytes: about 0.8 GB at
#: 10^5 faces (benchmarks/README.md); meshing alone takes about a quarter of it.
BYTES_PER_FACE = 8_000
#: Largest count a density file may give a group (``min_count`` too): one side cut in 10^5 pieces is
#: already a mesh of at least 10^5 faces.
MAX_COUNT = 100_000
#: Largest number of smoothing iterations an option accepts (``--smooth``, ``--surface-smooth``): the
#: smoothing settles in tens; 10^5 ran for many minutes.
MAX_ITERATIONS = 1000
