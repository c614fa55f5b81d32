"""Commands written for the CLI, waiting to be wired into ``vines.cli`` by the coordinator."""
