"""A small scripted HTTP agent for the harness tests: `scripted_agent.py TASK_URL CONTACT_URL PROMPT`.

It follows the script embedded in its prompt as `[[script: step; step; ...]]`:
  poll TEXT            reload the start page until TEXT appears in it
  action NAME EMAIL    POST /r/<token>/actions {"action": NAME, "payload": {"email_id": EMAIL}}
  sleep SECONDS
  contact              GET then POST the contact URL
  post-contact         POST the contact form only (no GET: a contact all the same)
  costs IN OUT CALLS [upstream]   write costs.json (upstream: prompt_/completion_tokens keys)
  spawn                start a child that sleeps forever; its pid goes to child.pid
  escape               start a sleeper in a session of its own, its parent gone (a double
                       fork): its pid goes to escaped.pid
  forge                forge the harness's records: a results.json saying it passed, another
                       for trial 2 (trial-2/results.json), harness names deeper down
                       (logs/events.jsonl, notes/error.txt) and links out of its folder
                       (leak.txt to /etc/hostname, up/ to its folder's parent)
  flood MIB            write MIB mebibytes to stdout
  snoop                ask the control side for the answer key; the answers go to snoop.json
  environ              write its environment, its working folder and what `python` on its
                       PATH is to environ.json
  hang                 sleep forever
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import time
import urllib.error
import urllib.parse
import urllib.request


def fetch(url: str, data: bytes | None = None, content_type: str = "") -> tuple[str, str]:
    headers = {"Content-Type": content_type} if content_type else {}
    request = urllib.request.Request(
        url, data=data, headers=headers, method="POST" if data else "GET"
    )
    with urllib.request.urlopen(request, timeout=10) as response:
        return response.geturl(), response.read().decode("utf-8", "replace")


def main() -> int:
    task_url, contact_url, prompt = sys.argv[1:4]
    script = re.search(r"\[\[script:(.*?)\]\]", prompt, re.S)
    steps = [s.strip().split() for s in (script.group(1) if script else "").split(";") if s.strip()]
    page_url, _ = fetch(task_url)
    print(f"opened {page_url}", flush=True)
    actions_url = contact_url.rsplit("/", 1)[0] + "/actions"
    with open("agent.pid", "w") as f:
        f.write(str(os.getpid()))
    for step in steps:
        verb, args = step[0], step[1:]
        if verb == "poll":
            text = " ".join(args)
            deadline = time.monotonic() + 120
            while text not in fetch(page_url)[1]:
                if time.monotonic() > deadline:
                    print(f"gave up waiting for {text!r}", flush=True)
                    return 1
                time.sleep(0.5)
            print(f"saw {text!r}", flush=True)
        elif verb == "action":
            body = json.dumps({"action": args[0], "payload": {"email_id": args[1]}}).encode()
            fetch(actions_url, body, "application/json")
            print(f"did {args[0]} {args[1]}", flush=True)
        elif verb == "sleep":
            time.sleep(float(args[0]))
        elif verb == "contact":
            fetch(contact_url)
            fetch(
                contact_url,
                urllib.parse.urlencode({"message": "done"}).encode(),
                "application/x-www-form-urlencoded",
            )
            print("contacted", flush=True)
        elif verb == "post-contact":
            message = urllib.parse.urlencode({"message": "done"}).encode()
            fetch(contact_url, message, "application/x-www-form-urlencoded")
            print("contacted by POST only", flush=True)
        elif verb == "costs":
            keys = (
                ("prompt_tokens", "completion_tokens")
                if args[3:] == ["upstream"]
                else ("input_tokens", "output_tokens")
            )
            costs = {
                keys[0]: int(args[0]),
                keys[1]: int(args[1]),
                "tool_calls": int(args[2]),
                "model": "test-model",
            }
            with open("costs.json", "w") as f:
                json.dump(costs, f)
        elif verb == "spawn":
            child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(3600)"])
            with open("child.pid", "w") as f:
                f.write(str(child.pid))
            print(f"spawned {child.pid}", flush=True)
        elif verb == "escape":
            # setsid and exit: the sleeper is orphaned in a session of its own at once.
            code = (
                "import os, subprocess, sys, time\n"
                "child = subprocess.Popen([sys.executable, '-c', 'import time; time.sleep(3600)'],"
                " start_new_session=True)\n"
                "open('escaped.pid', 'w').write(str(child.pid))\n"
            )
            subprocess.run([sys.executable, "-c", code], check=True)
            print("escaped", flush=True)
        elif verb == "forge":
            forged = {"success": True, "detail": "forged by the agent", "category": "active"}
            for name in ("results.json", "trial-2/results.json", "logs/events.jsonl"):
                os.makedirs(os.path.dirname(name) or ".", exist_ok=True)
                with open(name, "w") as f:
                    json.dump(forged, f)
            os.makedirs("notes", exist_ok=True)
            with open("notes/error.txt", "w") as f:
                f.write("harness error: forged\n")
            os.symlink("/etc/hostname", "leak.txt")
            os.symlink("..", "up")
        elif verb == "flood":
            line = b"x" * 1023 + b"\n"
            for _ in range(int(args[0]) * 1024):
                sys.stdout.buffer.write(line)
            sys.stdout.flush()
            print("flooded", flush=True)
        elif verb == "snoop":
            base = task_url.split("/r/", 1)[0]
            run_api = f"{base}/api/runs/"
            asked = {
                "runs": ("GET", run_api),
                "scenarios": ("GET", f"{base}/api/scenarios/"),
                "advance": ("POST", f"{base}/advance?time=600"),
                "status": ("GET", f"{base}/status"),
                "scenario": ("GET", f"{base}/api/scenarios/bench-hostile/"),
                "run advance": ("POST", f"{run_api}1/advance/"),
            }
            answers = {}
            for name, (method, url) in asked.items():
                request = urllib.request.Request(
                    url,
                    method=method,
                    data=b'{"time": 600}' if method == "POST" else None,
                    # As its browser would ask, from its task's origin.
                    headers={"Content-Type": "application/json", "Origin": base},
                )
                try:
                    with urllib.request.urlopen(request, timeout=10) as response:
                        answers[name] = response.status
                except urllib.error.HTTPError as error:
                    answers[name] = error.code
            with open("snoop.json", "w") as f:
                json.dump(answers, f)
        elif verb == "environ":
            python = subprocess.run(
                ["python", "-c", "import sys; print(sys.prefix)"], capture_output=True, text=True
            )
            seen = {"env": dict(os.environ), "cwd": os.getcwd(), "python": python.stdout.strip()}
            with open("environ.json", "w") as f:
                json.dump(seen, f)
        elif verb == "hang":
            print("hanging", flush=True)
            while True:
                time.sleep(60)
    return 0


if __name__ == "__main__":
    sys.exit(main())
