"""The limits of the server's requests (its docstring states them, from these constants)."""

MAX_BODY = 1 << 20  # bytes of a request body, plus BODY_PER_FACE per face of the mesh (Session.max_body)
BODY_PER_FACE = 128  # a pin [f, [x, y, z]] with 17-digit numbers takes ~80 bytes: every face can be pinned
MAX_SEEDS = 100000
DEFAULT_SEEDS = 3000
RAY_STEPS = 500_000  # faces crossed by all the rays of a streamline request together, at most (~0.5 s at worst)
MAX_LOAD = 64 << 20  # bytes of a file to load
MAX_N = 64  # the largest symmetry order n a request may ask for
MAX_DIGITS = 1000  # digits of an integer in a request (Python refuses to convert more than 4300: a ValueError)
BODY_TIMEOUT = 30  # seconds for a request body to arrive once its headers have (408 after)
# save kinds: the ending their path must have ("" for any)
SAVE_KINDS = {"singularities": "", "constraints": "", "field": ".txt", "vtk": ".vtk", "ply": ".ply",
              "streamlines": ""}
MAX_QUADS = 500_000  # quads of a quad-mesh request, at most (the library refuses a smaller H: about 14 MB of frame)
QUAD_SIZE_EDGES = 4  # a quad-mesh request's default quad size, in mean edge lengths of the mesh
