"""The subcommands of ``xroute``, one module each; :mod:`xroute.cli.app` assembles them."""
