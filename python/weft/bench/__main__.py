"""`python3 -m weft.bench NAME [options]`: Weft's Python benchmarks. NAME: hat_controller."""

import sys


def main():
    names = {"hat_controller": "weft.bench.hat_controller"}
    if len(sys.argv) < 2 or sys.argv[1] not in names:
        print("usage: python3 -m weft.bench hat_controller [options] (--help for its options)",
              file=sys.stderr)
        return 2
    module = __import__(names[sys.argv[1]], fromlist=["main"])
    return module.main(sys.argv[2:])


if __name__ == "__main__":
    sys.exit(main())
