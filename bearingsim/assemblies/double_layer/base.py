"""What the torque and dynamic levels of the double-layer bearing share
(:class:`PartialDoubleLayer`): the options of the layer pair, the shaft flange, the speed variables
``w_shaft``, ``w_middle``, ``Rs`` and the shaft's speed drive, with their equations."""

from __future__ import annotations

from bearingsim.assemblies.double_layer.options import LayerPairOptions
from bearingsim.assemblies.double_layer.speed import _shaft_speed_input, speed_ratio
from bearingsim.components.connectors import Flange
from bearingsim.components.rotational import SpeedSource
from bearingsim.language import Assembly, Variable, connect, der
from bearingsim.validation import options_object


class PartialDoubleLayer(Assembly):
    """A layer pair on a shaft with a middle ring: the part both friction levels share.

    A subclass builds its ``middle`` (a :class:`~bearingsim.components.middle_ring.MiddleRing`)
    and its layers, then calls :meth:`_declare_speeds` and, after its connections,
    :meth:`_build_drive`; its equations start with :meth:`_speed_equations` and end with
    :meth:`_drive_equations`.

    Parameters
    ----------
    options : LayerPairOptions or None
        The level's options (None: the defaults of ``kind``).
    kind : type
        The level's options class, a :class:`LayerPairOptions`.
    name : str
        Instance name.

    Attributes
    ----------
    options : LayerPairOptions
    structure : {"I", "Z"}
    geometries : (BearingGeometry, BearingGeometry)
        Inner and outer layer.

    Connectors
    ----------
    shaft : Flange (inner ring of the inner bearing)
    """

    def __init__(self, options: LayerPairOptions | None, kind: type, name: str):
        super().__init__(name)
        self.options = options_object(options, kind, "double_layer_bearing")
        self.structure = self.options.structure
        self.geometries = self.options.geometries
        self.shaft = Flange()

    def _declare_speeds(self) -> None:
        """The variables ``w_shaft``, ``w_middle`` [rad/s] and ``Rs`` [1]."""
        self.w_shaft = Variable(unit="rad/s", description="shaft (inner ring) speed")
        self.w_middle = Variable(unit="rad/s", description="middle ring speed")
        self.Rs = Variable(unit="1", description="speed distribution ratio n_z / n_i")

    def _build_drive(self) -> None:
        """For ``drive="speed"`` a :class:`~bearingsim.components.rotational.SpeedSource` on
        the shaft, at the constant ``speed`` or the required input ``shaft_speed`` [rad/s]."""
        options = self.options
        if options.drive == "speed":
            self.drive = SpeedSource(options.speed)
            connect(self.drive.flange, self.shaft)
            if options.speed is None:
                self.shaft_speed = _shaft_speed_input(*self.geometries)

    def _speed_equations(self) -> list:
        """``w_shaft``, ``w_middle`` and ``Rs`` (:func:`speed_ratio`)."""
        return [
            self.w_shaft == der(self.shaft.phi),
            self.w_middle == self.middle.w,
            self.Rs == speed_ratio(self.w_middle, self.w_shaft),
        ]

    def _drive_equations(self) -> list:
        """The speed source follows the input ``shaft_speed`` where there is one."""
        return [self.drive.w_in == self.shaft_speed] if hasattr(self, "shaft_speed") else []
