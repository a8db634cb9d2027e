"""The inputs of the Magic Formula's steady state, as one table (no numpy: the CLI reads it
when it builds its parser).

:data:`INPUTS` lists them (name -> unit, meaning, the quantity its values are, the unit a
bare number is read in at the command line, the default): what
:func:`~frictionlaws.tyre.mf.outputs.steady_state` takes, what the CLI makes its options of
(``tyre mf FILE --kappa ... --alpha ...``), what JSON and xarray results name.  A new input
is one row here, one argument of the steady state and its use in the equations.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Input", "INPUTS"]


@dataclass(frozen=True)
class Input:
    """One input of the steady state.

    Attributes
    ----------
    unit : str
        SI unit (``"1"``: dimensionless).
    meaning : str
        What it is.
    quantity : str
        The kind of quantity (:data:`frictionlaws.base.units.QUANTITIES`) its values are read as.
    display : str
        The unit a bare number is read in at the command line.
    default : str
        What is taken when it is not given.
    """

    unit: str
    meaning: str
    quantity: str
    display: str
    default: str


#: The inputs of :func:`~frictionlaws.tyre.mf.outputs.steady_state`, in its argument order.
INPUTS: dict[str, Input] = {
    "kappa": Input("1", "longitudinal slip ratio (positive when driving)", "s", "-", "0"),
    "alpha": Input("rad", "slip angle", "angle", "deg", "0"),
    "fz": Input("N", "vertical load", "F_N", "kN", "FNOMIN"),
    "gamma": Input("rad", "inclination (camber) angle", "angle", "deg", "0"),
    "pressure": Input("Pa", "inflation pressure", "p", "kPa", "the file's INFLPRES / IP"),
    "vx": Input("m/s", "forward speed (negative: running backwards)", "v", "m/s",
                "the file's LONGVL"),
    "phit": Input("1/m", "turn slip: the curvature of the wheel's path (needs the turn-slip "
                  "model)", "curvature", "1/m", "0"),
    "omega": Input("rad/s", "wheel angular speed", "angular_velocity", "rad/s",
                   "from the slip ratio and the effective rolling radius"),
}
