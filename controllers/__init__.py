"""controllers: explicit model following, ADS-33-style specs, CasADi design-margin optimisation."""
__all__: list = []
