"""The defaults of every call: the library's table (study/defaults.hpp), which `gyrokit defaults` prints and
docs/defaults.md lists. The signatures take their values from here, so that none is decided twice."""
from . import _core

TABLE = tuple(dict(row) for row in _core.defaults())
_VALUE = {row["name"]: row["value"] for row in TABLE}

METHOD = _VALUE["method"]
LANCZOS = int(_VALUE["lanczos"])
JOBS = int(_VALUE["jobs"])
TOLERANCE = float(_VALUE["tolerance"])
GRAVITY = float(_VALUE["gravity"])
MAP_MODES = int(_VALUE["map modes"])
LEVEL1_INTERVALS = int(_VALUE["intervals"])
API_SPEEDS = int(_VALUE["api speeds"])
MESH_TOLERANCE = float(_VALUE["mesh tolerance"])
MESH_LEVELS = int(_VALUE["mesh levels"])
MODE_SHAPES = int(_VALUE["mode shapes"])
MAX_STEPS = int(_VALUE["max steps"])
START = _VALUE["start"]
