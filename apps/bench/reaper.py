"""Runs one agent for the harness and leaves nothing of it behind.

    python apps/bench/reaper.py --output OUTPUT --cap BYTES [--shell] -- COMMAND [ARG …]

(Run by its path, standard library only: the agent's environment needs no path of the project.)

- **No descendant outlives the task.** The reaper is a child subreaper (Linux prctl
  PR_SET_CHILD_SUBREAPER): a process the agent starts and abandons — `setsid()`, a double fork —
  becomes the reaper's child instead of init's. When the agent exits, or the harness says stop
  (SIGTERM), the reaper kills the agent's process group, then every process left under it,
  until none is; killing the agent's whole group was not enough (a `setsid()` grandchild outlived
  its task and the harness).
- **The output is capped.** The agent's stdout and stderr go through the reaper into OUTPUT:
  the first and the last BYTES/2 are kept and the cut is said in between (an agent wrote
  300 MiB in 2 s).
- The reaper's first line on its own stdout is `agent <pid>`, so the harness can still kill
  the agent's group should the reaper itself be killed. It exits as the agent did.
"""

from __future__ import annotations

import argparse
import contextlib
import ctypes
import os
import signal
import subprocess
import sys
import threading
from collections import deque
from pathlib import Path

PR_SET_CHILD_SUBREAPER = 36
CHUNK = 65_536


def become_subreaper() -> None:
    with contextlib.suppress(OSError, AttributeError):
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_CHILD_SUBREAPER, 1)


class CappedOutput:
    """Writes the first `cap // 2` bytes through, keeps the last `cap // 2`, says the cut."""

    def __init__(self, path: Path, cap: int):
        self.file = open(path, "wb")  # noqa: SIM115 - closed by finish()
        self.head_left = cap // 2
        self.tail: deque[bytes] = deque()
        self.tail_size = 0
        self.tail_cap = cap - cap // 2
        self.cut = 0

    def write(self, data: bytes) -> None:
        if self.head_left > 0:
            head, data = data[: self.head_left], data[self.head_left :]
            self.file.write(head)
            self.file.flush()
            self.head_left -= len(head)
        if not data:
            return
        self.tail.append(data)
        self.tail_size += len(data)
        while self.tail_size > self.tail_cap:
            over = self.tail_size - self.tail_cap
            first = self.tail[0]
            if len(first) <= over:
                self.tail.popleft()
                dropped = len(first)
            else:
                self.tail[0] = first[over:]
                dropped = over
            self.tail_size -= dropped
            self.cut += dropped

    def finish(self) -> None:
        if self.cut:
            self.file.write(f"\n[… {self.cut:,} bytes of output cut by the harness …]\n".encode())
        for part in self.tail:
            self.file.write(part)
        self.file.close()


def pump(source, sink: CappedOutput) -> None:
    while chunk := source.read1(CHUNK):
        sink.write(chunk)


def children() -> list[int]:
    mine = os.getpid()
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        if int(stat.rsplit(")", 1)[1].split()[1]) == mine:
            found.append(int(entry.name))
    return found


def kill_everything_under_me(agent_group: int) -> None:
    """Kill the agent's group, then whatever is left under this process, until nothing is."""
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(agent_group, signal.SIGKILL)
    while True:
        left = children()
        if not left:
            return
        for pid in left:
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.killpg(pid, signal.SIGKILL)  # an escaped one leads its own group
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.kill(pid, signal.SIGKILL)
        for pid in left:
            with contextlib.suppress(ChildProcessError):
                os.waitpid(pid, 0)


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="reaper.py")
    parser.add_argument("--output", type=Path, required=True)
    parser.add_argument("--cap", type=int, required=True)
    parser.add_argument("--shell", action="store_true")
    parser.add_argument("command", nargs="+")
    args = parser.parse_args(argv)
    become_subreaper()
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    output = CappedOutput(args.output, args.cap)
    command = args.command[0] if args.shell else args.command
    try:
        agent = subprocess.Popen(
            command,
            shell=args.shell,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
    except OSError as exc:
        output.write(f"could not launch the agent {command!r}: {exc}\n".encode())
        output.finish()
        return 127
    print(f"agent {agent.pid}", flush=True)
    pumping = threading.Thread(target=pump, args=(agent.stdout, output), daemon=True)
    pumping.start()
    while agent.poll() is None and not stop.wait(0.1):
        pass
    kill_everything_under_me(agent.pid)
    code = agent.wait()
    pumping.join(timeout=10)  # every writer is gone: the pipe has ended
    output.finish()
    if code < 0:  # died of a signal: say so as the agent's own exit would have
        signal.signal(-code, signal.SIG_DFL)
        os.kill(os.getpid(), -code)
    return code


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
