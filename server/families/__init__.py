"""The slider-family engine: an endpoint's answer at values across a slider's range, interpolated between them
with a bounded error and refined until the bound holds (pure numerics; no HTTP)."""
