# LeatherCut -- developer shortcuts over bootstrap.sh (the README's two commands).
.PHONY: setup demo test bench screenshots clean

setup:
	@bash tools/setup.sh

demo:
	@bash bootstrap.sh demo

test:
	@bash bootstrap.sh test

bench:
	@bash bootstrap.sh bench

screenshots: setup
	@.venv/bin/python tools/screenshots.py

clean:
	rm -rf out .pytest_cache
