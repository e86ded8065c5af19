"""Run an Athena 4.2 (C version) build given by the user, side by side with dustygas.

Nothing of Athena is shipped here: the benchmark scripts take the path of an ``athena`` binary
built outside the repository and of the input file of its problem (by default looked up in the
Athena source tree above the binary: ``tst/particle/athinput.<problem>``), and pass every
parameter that matters on Athena's command line (``block/name=value``), so that the run is the
one described in the script whatever the input file says.

How to build the binaries (words, not a recipe): from the public Athena 4.2 C repository,
``configure`` with ``--with-gas=hydro --with-eos=isothermal --enable-shearing-box
--with-integrator=ctu --with-order=3p --with-flux=hllc`` and, for the particle runs, also
``--with-particles=feedback --enable-fargo --with-problem=streaming2d_single``; for the gas-only
rows ``--with-problem=hb3`` (2D x-z) or ``--with-problem=hgb`` (3D); then ``make all`` (recent
gcc needs ``-fcommon`` in the compiler flags; GNU make 4.4 stops at the ``abort`` line of the
generated ``Makeoptions``' machine list, which can be blanked). One binary per problem; for runs on
several MPI ranks (``run_athena(..., ranks=N)``) add ``--enable-mpi`` (mpich's ``mpicc``).
"""

from __future__ import annotations

import re
import resource
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

#: the columns of the mode-amplitude file of Athena's streaming2d problems: the largest |perturbation|
#: of each field over the grid (gas density, dust density, then gas/dust velocities x, y, z)
STREAMING_COLUMNS = ("drho_g", "drho_p", "ux", "wx", "uy", "wy", "uz", "wz")

#: input of Athena's ``par_strat3d`` / ``par_strat2d`` with the physics of dustygas's ``si3d``
#: preset: one species of τ_s = 1 (fixed), Z = 0.03 in a Gaussian layer of H_p = 0.02 H, Π = 0.05
#: (``vsc1``), the NSH start (``ipert = 0``), TSC and the semi-implicit integrator; periodic
#: boundaries (Athena's potential is periodic in z). The caller fills in the box (``n``, ``lo``,
#: ``hi`` per axis; x1 radial, and in 2D x2 vertical), the one output block, the time limits,
#: ``NGrid_x1`` (``ranks``) and the particles per grid (one per cell: cells / ranks).
PAR_STRAT_INPUT = """<job>
problem_id = {problem_id}
maxout = 1
num_domains = 1
<output1>
out_fmt = {out_fmt}
dt = {out_dt}
<time>
cour_no = {courant}
nlim = {nlim}
tlim = {tlim}
<domain1>
level = 0
Nx1 = {n1}
x1min = {lo1}
x1max = {hi1}
bc_ix1 = 4
bc_ox1 = 4
NGrid_x1 = {ranks}
Nx2 = {n2}
x2min = {lo2}
x2max = {hi2}
bc_ix2 = 4
bc_ox2 = 4
NGrid_x2 = 1
Nx3 = {n3}
x3min = {lo3}
x3max = {hi3}
bc_ix3 = 4
bc_ox3 = 4
NGrid_x3 = 1
<particle>
partypes = 1
parnumgrid = {per_grid}
integrator = 2
interp = 2
tsmode = 3
tshuf = 2000
<problem>
omega = 1.0
iso_csound = 1.0
tsmin = 1.0
tsmax = 1.0
tscrit = 0.01
hparmax = 0.02
hparmin = 0.02
amin = 1.0
amax = 1.0
rhoaconv = 1.0
alamcoeff = 1.0
mratio = 0.03
pwind = 0.0
vsc1 = 0.05
vsc2 = 0.0
ipert = 0
ntrack = 0
nlis = 0
"""


def find_input(binary: Path, problem: str, subdir: str) -> Path:
    """``tst/<subdir>/athinput.<problem>`` of the Athena source tree above ``binary``."""
    for parent in binary.resolve().parents:
        for tree in (parent, *parent.glob("*/")):
            candidate = tree / "tst" / subdir / f"athinput.{problem}"
            if candidate.is_file():
                return candidate
    raise SystemExit(f"no athinput.{problem} found above {binary}: pass --athinput")


def run_athena(binary: Path, athinput: Path, overrides: list[str], workdir: Path | None = None,
               ranks: int = 1) -> dict:
    """Run ``binary -i athinput overrides...`` in a scratch directory (``ranks > 1``: through
    ``mpiexec -n ranks``, for a binary configured with ``--enable-mpi``); wall and CPU time (of
    all ranks), cycles, output."""
    with tempfile.TemporaryDirectory(dir=workdir) as tmp:
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        launcher = ["mpiexec", "-n", str(ranks)] if ranks > 1 else []
        proc = subprocess.run([*launcher, str(binary), "-i", str(athinput), *overrides], cwd=tmp,
                              capture_output=True, text=True, check=False)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        if proc.returncode != 0:
            raise SystemExit(f"athena failed ({proc.returncode}): {proc.stderr[-500:] or proc.stdout[-500:]}")
        out = proc.stdout
        cycles = [int(c) for c in re.findall(r"^cycle=(\d+)", out, flags=re.M)]
        files = {p.name: p.read_text() for p in Path(tmp).glob("*.dat")}
    return {"wall": wall, "cpu": cpu, "cycles": cycles[-1] if cycles else 0, "stdout": out, "files": files}


def streaming_growth(text: str):
    """Growth fit of the eight fields of an Athena streaming2d amplitude file (max |perturbation|
    against time), with dustygas's automatic linear window
    (:func:`dustygas.analysis.growth.measure_growth`)."""
    from dustygas.analysis.growth import measure_growth

    data = np.loadtxt(text.splitlines())
    t = data[:, 0]
    modes = {name: data[:, 1 + i].astype(np.complex128) for i, name in enumerate(STREAMING_COLUMNS)}
    return measure_growth((t, modes))
