"""The tabulated loads the wear endpoint takes instead of the kinetostatics: reactions at crank angles."""
from __future__ import annotations

from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field, model_validator

MAX_ROWS = 721

Angle = Annotated[float, Field(ge=-720, le=720, allow_inf_nan=False)]
Force = Annotated[float, Field(ge=-1e8, le=1e8, allow_inf_nan=False)]
Ratio = Annotated[float, Field(ge=-100, le=100, allow_inf_nan=False)]


class TabulatedReactions(BaseModel):
    """A table like Chaika–Vasylenko's Table 4.3: rows at crank angles φ₁ from 0 to 360° (the last repeating
    the first), summed by trapezoids over the rows as the book does (§4.2)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    phi: list[Annotated[float, Field(ge=0, le=360, allow_inf_nan=False)]] = Field(
        min_length=5, max_length=MAX_ROWS, description="crank angles φ₁, deg: 0 first, 360 last, increasing")
    R23: list[Annotated[float, Field(ge=0, le=1e8, allow_inf_nan=False)]] = Field(
        max_length=MAX_ROWS, description="|R₂₃|, the rod's force on the piston pin, N")
    gamma32: list[Angle] = Field(max_length=MAX_ROWS, description="γ₃₂, its direction, deg")
    R34: list[Force] = Field(max_length=MAX_ROWS, description="the guide's reaction on the piston, N (+: the right side)")
    u21: list[Ratio] = Field(max_length=MAX_ROWS, description="u₂₁ = ω₂/ω₁")
    phi2: list[Angle] = Field(max_length=MAX_ROWS, description="φ₂, the rod's angle, deg")
    V_qB: list[Ratio] = Field(max_length=MAX_ROWS, description="the piston's velocity analog, m/rad")
    l1: float = Field(gt=0, le=100, allow_inf_nan=False, description="crank length of the table's mechanism, m")
    l2: float = Field(gt=0, le=1000, allow_inf_nan=False, description="rod length (axial mechanism), m")

    @model_validator(mode="after")
    def one_cycle(self):
        rows = len(self.phi)
        columns = ("R23", "gamma32", "R34", "u21", "phi2", "V_qB")
        if any(len(getattr(self, name)) != rows for name in columns):
            raise ValueError(f"every column has one value per angle: {rows} rows")
        if rows % 2 == 0:
            raise ValueError("an even number of intervals (an odd number of rows): the sums are compared with "
                             "those over every other row")
        if self.phi[0] != 0 or self.phi[-1] != 360 or any(b <= a for a, b in zip(self.phi, self.phi[1:])):
            raise ValueError("phi runs from 0 to 360 degrees, increasing")
        if self.l2 <= self.l1:
            raise ValueError("the rod l2 must be longer than the crank l1")
        if max(self.R23) == 0 or max(self.R34) <= 0:
            raise ValueError("wear needs a load: R23 somewhere above 0 and R34 pressing the right side (> 0) in "
                             "some row (k = I_s/p_m divides by the mean pressures)")
        return self

    def columns(self) -> dict:
        return self.model_dump(exclude={"l1", "l2"})
