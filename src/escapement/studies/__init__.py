"""Studies beyond the paper's figures. Import the module you need: the package imports none of them, so that a
job loads only the studies it runs."""
