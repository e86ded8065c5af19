import sys
from pathlib import Path

# make the test-only toy problem importable by tests and by the subprocesses they start
TESTS = Path(__file__).parent
if str(TESTS) not in sys.path:
    sys.path.insert(0, str(TESTS))

# Under pytest-xdist (README's test command and .ci/run's slow tests run on two workers, one file per
# worker at a time) the files that take longest are handed out first, so that the two workers finish
# together instead of one starting linB (the longest) when the other is done. The order is otherwise
# the collection's. The slow files come first; the default suite's longest files (CPU-s with a cold
# kernel cache, 2026-12-03) follow -- a slow file's default-suite tests are few and short.
LONGEST_FIRST = ("particles/test_linb_slow.py", "linear/test_particle_modes_slow.py",
                 "outputs/test_gallery.py", "particles/test_streaming_slow.py", "sph/test_sod.py",
                 "dustysph/test_phantom_dustywave.py", "sph/test_disk_slow.py",
                 "grid/test_ctu.py", "outputs/test_plot.py", "dustysph/test_dust_diffusion.py",
                 "problems/test_registry.py", "linear/test_cli_linear.py", "particles/test_streaming.py",
                 "linear/test_angle.py", "mpi/test_particles_mpi.py", "mpi/test_gas_decomposition.py")


def pytest_collection_modifyitems(config, items):
    if not getattr(config.option, "numprocesses", None):
        return
    rank = {name: i for i, name in enumerate(LONGEST_FIRST)}

    def key(item):
        path = Path(str(item.fspath)).resolve()
        rel = path.relative_to(TESTS.resolve()).as_posix() if path.is_relative_to(TESTS.resolve()) else ""
        return rank.get(rel, len(rank))

    items.sort(key=key)
