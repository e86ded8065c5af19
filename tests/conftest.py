import sys
from pathlib import Path

# make the test-only toy problem importable by tests and by the subprocesses they start
TESTS = Path(__file__).parent
if str(TESTS) not in sys.path:
    sys.path.insert(0, str(TESTS))
