from xroute_cli.app import main

main()
