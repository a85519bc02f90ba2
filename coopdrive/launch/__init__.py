"""Starting a whole run: the simulator and every vehicle's services as separate processes."""
