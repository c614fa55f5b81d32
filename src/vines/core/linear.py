"""The stuck linear system (paper Eq. 28): ball and LO moving together as one body.

    (1 + eta) z'' + d z' + z = F sin(omega t) + d omega F cos(omega t)

Its steady-state amplitude is the reference curve of Fig. 11 (x_max of the VINES against
the response of the LO with the ball stuck to a wall, natural frequency 1/sqrt(1 + eta)).
"""
from __future__ import annotations

import numpy as np

from .params import D_DEFAULT


def stuck_amplitude(eta, omega, F, d=D_DEFAULT):
    """Steady-state amplitude of z (units of L) of Eq. 28; broadcasts over its arguments.

    The forcing F (sin + d omega cos) has amplitude F sqrt(1 + (d omega)^2), the receptance is
    1 / |1 - (1 + eta) omega^2 + i d omega|, so

        |z| = F sqrt(1 + (d omega)^2) / sqrt((1 - (1 + eta) omega^2)^2 + (d omega)^2).

    Infinite at resonance omega = 1/sqrt(1 + eta) when d = 0.
    """
    eta, omega, F, d = (np.asarray(x, dtype=float) for x in (eta, omega, F, d))
    dw = d * omega
    den = np.hypot(1.0 - (1.0 + eta) * omega ** 2, dw)
    with np.errstate(divide="ignore", invalid="ignore"):
        amp = F * np.sqrt(1.0 + dw ** 2) / den
    amp = np.where((den == 0) & (F == 0), 0.0, amp)
    return amp[()] if amp.ndim == 0 else amp


def stuck_peak(eta, F, d=D_DEFAULT):
    """(omega, amplitude) of the maximum of ``stuck_amplitude`` over omega, in closed form.

    With u = omega^2 and a = 1 + eta, d|z|^2/du = 0 reduces to a d^2 u^2 + 2 a u - 2 = 0, whose
    positive root is u = 2 / (a + sqrt(a^2 + 2 a d^2)) (the form without cancellation for
    small d); the peak lies just below 1/sqrt(1 + eta). Needs d > 0 (d = 0: infinite peak).
    """
    eta, F, d = (np.asarray(x, dtype=float) for x in (eta, F, d))
    a = 1.0 + eta
    omega = np.sqrt(2.0 / (a + np.sqrt(a * a + 2.0 * a * d * d)))
    return omega[()], stuck_amplitude(eta, omega, F, d)


def stuck_steady_state(t, eta, omega, F, d=D_DEFAULT, phi=0.0):
    """The steady-state displacement z(t) (units of L) of Eq. 28 forced with the phase
    ``phi``: F sin(omega t + phi) + d omega F cos(omega t + phi); the imaginary part of
    H e^(i (omega t + phi)), H = F (1 + i d omega) / (1 - (1 + eta) omega^2 + i d omega)."""
    H = F * (1 + 1j * d * omega) / (1 - (1 + eta) * omega ** 2 + 1j * d * omega)
    return np.imag(H * np.exp(1j * (omega * t + phi)))
