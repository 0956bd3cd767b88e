"""The ``xroute`` command: assembles the subcommands (one module each)."""

from __future__ import annotations

import typer

app = typer.Typer(no_args_is_help=True, add_completion=False, help="xroute: a detailed router with learnable net ordering.")


@app.command()
def info(testcase: str) -> None:
    """Print a summary of a design."""
    from xroute_cli.design import load_design

    d = load_design(testcase)
    print(d)


def main() -> None:
    app()
