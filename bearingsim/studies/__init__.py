"""Studies: parameter sweeps and reproductions of the published cases."""
