"""A noisy neighbour for `bench_neighbours`: `--in-flight` requests at a time to one run's pages,
from a process of its own (so its client work never slows the measuring process).

    python -m apps.bench.flood BASE_URL PAGE [PAGE …] --in-flight 24 --seconds 10

Prints one line: `flood: pages=<n> errors=<n>`.
"""

from __future__ import annotations

import argparse
import asyncio
import sys
import time

import httpx


async def flood(base_url: str, pages: list[str], in_flight: int, seconds: float) -> tuple[int, int]:
    done = errors = 0
    deadline = time.monotonic() + seconds
    limits = httpx.Limits(max_connections=in_flight, max_keepalive_connections=in_flight)
    async with httpx.AsyncClient(base_url=base_url, timeout=30, limits=limits) as client:

        async def one_client(offset: int) -> None:
            nonlocal done, errors
            position = offset
            while time.monotonic() < deadline:
                try:
                    response = await client.get(pages[position % len(pages)])
                    done += response.status_code == 200
                    errors += response.status_code != 200
                except httpx.HTTPError:
                    errors += 1
                position += 1

        await asyncio.gather(*(one_client(i) for i in range(in_flight)))
    return done, errors


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="python -m apps.bench.flood")
    parser.add_argument("base_url")
    parser.add_argument("pages", nargs="+")
    parser.add_argument("--in-flight", type=int, default=24)
    parser.add_argument("--seconds", type=float, default=10.0)
    args = parser.parse_args(argv)
    done, errors = asyncio.run(flood(args.base_url, args.pages, args.in_flight, args.seconds))
    print(f"flood: pages={done} errors={errors}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
