"""The subcommands of ``xroute``, one module each; :mod:`xroute_cli.app` assembles them."""
