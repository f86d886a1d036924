"""The mechanisms of the kinematics chapter, one module each, sharing one interface."""
from .base import GeometryError, Notice, OutputSpec, ParamSpec, SpecialPosition
from .four_bar import FourBar
from .mechanism import Mechanism
from .sine import Sine
from .slider_crank import SliderCrank
from .slotted_link import SlottedLink

SLIDER_CRANK = SliderCrank()        # named by the modules that are by nature the crank-slider's
MECHANISMS: dict[str, Mechanism] = {m.name: m for m in (Sine(), SLIDER_CRANK, SlottedLink(), FourBar())}

__all__ = ["MECHANISMS", "SLIDER_CRANK", "GeometryError", "Mechanism", "Notice", "OutputSpec", "ParamSpec", "SpecialPosition"]
