// World implementation in progress.
