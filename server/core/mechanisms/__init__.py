"""The mechanisms of the kinematics chapter, one module each, sharing one interface."""
from .base import GeometryError, Notice, OutputSpec, ParamSpec, SpecialPosition
from .four_bar import FourBar
from .mechanism import Mechanism
from .sine import Sine
from .slider_crank import SliderCrank
from .slotted_link import SlottedLink

MECHANISMS: dict[str, Mechanism] = {m.name: m for m in (Sine(), SliderCrank(), SlottedLink(), FourBar())}

__all__ = ["MECHANISMS", "GeometryError", "Mechanism", "Notice", "OutputSpec", "ParamSpec", "SpecialPosition"]
