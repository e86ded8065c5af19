import sys
from pathlib import Path

# make the test-only toy problem importable by tests and by the subprocesses they start
TESTS = Path(__file__).parent
if str(TESTS) not in sys.path:
    sys.path.insert(0, str(TESTS))

# Under pytest-xdist (.ci/run runs the slow tests on two workers, one file per worker at a time) the
# files that take longest are handed out first, so that the two workers finish together instead of
# one starting linB (the longest) when the other is done. The order is otherwise the collection's.
LONGEST_FIRST = ("particles/test_linb_slow.py", "linear/test_particle_modes_slow.py",
                 "outputs/test_gallery.py", "particles/test_streaming_slow.py", "sph/test_sod.py",
                 "dustysph/test_phantom_dustywave.py", "sph/test_disk_slow.py")


def pytest_collection_modifyitems(config, items):
    if not getattr(config.option, "numprocesses", None):
        return
    rank = {name: i for i, name in enumerate(LONGEST_FIRST)}

    def key(item):
        path = Path(str(item.fspath)).resolve()
        rel = path.relative_to(TESTS.resolve()).as_posix() if path.is_relative_to(TESTS.resolve()) else ""
        return rank.get(rel, len(rank))

    items.sort(key=key)
