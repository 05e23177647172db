"""Hand-built plants the multi-axis tests share."""
import control
import numpy as np


def roll_pitch(c=0.0):
    """Roll p/delta_lat = 5/(s+1.5), pitch q/delta_lon = -4/(s+1), phi = int p, theta = int q;
    ``c`` couples p and q both ways (rad/s per rad/s)."""
    A = np.zeros((4, 4))
    A[0, 0], A[1, 0], A[2, 2], A[3, 2] = -1.5, 1.0, -1.0, 1.0
    A[0, 2] = A[2, 0] = c
    B = np.zeros((4, 2))
    B[0, 0], B[2, 1] = 5.0, -4.0
    return control.ss(A, B, np.eye(4), 0, inputs=["delta_lat", "delta_lon"], outputs=["p", "phi", "q", "theta"])
