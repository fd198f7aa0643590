"""Small vector helpers shared by the kernels."""
import math

from ._jit import njit


@njit
def norm(x, y):
    """Length of (x, y). Not math.hypot: glibc's hypot guards against
    overflow and underflow at several times the cost of a square root (it
    was 16% of the event solver's time), and the kernels' lengths, speeds
    and spins (1e-15 .. 1e3) are far from both limits. Values so small that
    their squares underflow come out 0, which every caller treats as 'at
    rest' or 'slip ended', as it must."""
    return math.sqrt(x * x + y * y)
