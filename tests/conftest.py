import matplotlib

# Library code never touches global pyplot state, but tests that call .plot()
# need a non-interactive backend on headless CI machines.
matplotlib.use("Agg")
