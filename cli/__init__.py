"""The ``xroute`` command (Typer): :mod:`xroute.cli.app` assembles one module per command from
:mod:`xroute.cli.commands`; console output, progress and the batch runner live beside them.

The top layer of the package: nothing below it imports from here.
"""
