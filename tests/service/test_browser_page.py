#!/usr/bin/env python3
"""The page at / in a real browser (issue 14, docs/web.md).

The system shall serve a page that submits a bundled example, plots its series while it runs (the number of
points grows), reaches `succeeded` with every step plotted once, offers a working download of the result,
shows validation errors next to the field their JSON pointer names and the scene's warnings, labels log axes by
decades without repeats, filters the job list by status, plots a study's accuracy against time with its table
(every point labelled with its h; tolerances as a line of their own, labelled TOL), plots the step size of a
run with time.tolerance, fits 1280 px without overflow, and asks for the bearer token when the server
has one.

Starts `stoss serve` on 127.0.0.1 (port 0) and Debian's headless Chromium, drives the page through the
DevTools protocol (python3-websocket), asserts on the DOM and saves screenshots under BUILD/browser/.
Usage: test_browser_page.py STOSS_BINARY BUILD_DIR
"""
import base64
import itertools
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

import websocket

HDF5_SIGNATURE = [0x89, 0x48, 0x44, 0x46, 0x0D, 0x0A, 0x1A, 0x0A]
# The verdict cell of the job's summary table (null while the run goes on shows as "made when the run ends").
VERDICT_SHOWN = "document.querySelector('#job-summary tr[data-key=verdict] td')?.textContent ?? null"
EXAMPLE = "hollow_ball_plate"   # contact, 100 steps: a few seconds of run to watch
EXAMPLE_ROWS = 101               # t0 and 100 steps
CHECKS = {"passed": 0, "failed": 0}


def check(condition, what):
    """Counts and prints one assertion; the test fails at the end if any failed."""
    CHECKS["passed" if condition else "failed"] += 1
    print(("ok      " if condition else "FAILED  ") + what, flush=True)
    return condition


class Server:
    """`stoss serve` on a free loopback port with its own data directory."""

    def __init__(self, binary, data, *flags):
        self.process = subprocess.Popen([binary, "serve", "--listen", "127.0.0.1:0", "--data", str(data),
                                         "--workers", "1", *flags],
                                        stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        line = self.process.stdout.readline()
        match = re.search(r"listening on (http://127\.0\.0\.1:\d+)", line)
        if not match:
            self.process.kill()
            self.process.wait()
            raise RuntimeError("stoss serve did not start: " + line)
        self.url = match.group(1)

    def post(self, path, body):
        request = urllib.request.Request(self.url + path, data=json.dumps(body).encode(),
                                         headers={"Content-Type": "application/json"})
        with urllib.request.urlopen(request, timeout=30) as response:
            return json.load(response)

    def stop(self):
        self.process.terminate()
        self.process.wait(timeout=30)


class Browser:
    """Headless Chromium with one page, driven over the DevTools protocol."""

    def __init__(self, profile):
        self.process = subprocess.Popen(
            ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
             "--remote-debugging-port=0", "--user-data-dir=" + str(profile), "--window-size=1400,2400",
             "about:blank"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            self.connect(profile)
        except Exception:
            self.process.kill()
            self.process.wait()
            raise

    def connect(self, profile):
        port_file = Path(profile) / "DevToolsActivePort"
        deadline = time.monotonic() + 60
        while not (port_file.exists() and port_file.read_text().strip()):
            if time.monotonic() > deadline or self.process.poll() is not None:
                raise RuntimeError("chromium did not open its DevTools port")
            time.sleep(0.1)
        port = port_file.read_text().split()[0]
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=30) as response:
            page = next(t for t in json.load(response) if t["type"] == "page")
        self.socket = websocket.create_connection(page["webSocketDebuggerUrl"], timeout=60)
        self.ids = itertools.count(1)
        self.call("Page.enable")
        self.call("Runtime.enable")

    def call(self, method, **params):
        id_ = next(self.ids)
        self.socket.send(json.dumps({"id": id_, "method": method, "params": params}))
        while True:
            message = json.loads(self.socket.recv())
            if message.get("id") == id_:
                if "error" in message:
                    raise RuntimeError(f"{method}: {message['error']}")
                return message["result"]

    def run(self, expression):
        """The value of a JavaScript expression in the page (promises awaited)."""
        result = self.call("Runtime.evaluate", expression=expression, awaitPromise=True, returnByValue=True)
        if "exceptionDetails" in result:
            raise RuntimeError(f"{expression}: {result['exceptionDetails']}")
        return result["result"].get("value")

    def wait_for(self, expression, what, limit=60):
        """Polls `expression` until it is truthy; a page that never gets there fails the check (a bound, not
        a timing the test measures)."""
        deadline = time.monotonic() + limit
        while time.monotonic() < deadline:
            if self.run(f"!!({expression})"):
                return True
            time.sleep(0.1)
        check(False, what + f" (not within {limit} s)")
        raise SystemExit(1)

    def open(self, url):
        self.call("Page.navigate", url=url)
        self.wait_for("document.readyState === 'complete' && typeof Dygraph === 'function'", "page loaded")

    def screenshot(self, path):
        data = self.call("Page.captureScreenshot", format="png")["data"]
        Path(path).write_bytes(base64.b64decode(data))
        print("screenshot " + str(path), flush=True)

    def stop(self):
        self.socket.close()
        self.process.terminate()
        self.process.wait(timeout=30)


def js(value):
    return json.dumps(value)


def choose(browser, select_id, value):
    """Picks `value` in the <select> `select_id` as a user would (a change event follows)."""
    browser.run(f"(() => {{ const s = document.getElementById({js(select_id)}); s.value = {js(value)};"
                f" s.dispatchEvent(new Event('change')); }})()")


def click_job_row(browser, job_id):
    """Clicks the job's row in the list once the list shows it."""
    row = f"document.querySelector('#jobs tr[data-id=\"{job_id}\"]')"
    browser.wait_for(row, f"the job {job_id} is listed")
    browser.run(row + ".click()")


def set_scene_and_submit(browser, scene):
    browser.run(f"document.getElementById('scene-text').value = {js(json.dumps(scene, indent=2))}")
    browser.run("document.getElementById('submit-button').click()")


def validation_errors_next_to_fields(browser):
    choose(browser, "example", EXAMPLE)
    scene = json.loads(browser.run("document.getElementById('scene-text').value"))
    check(scene.get("contact"), f"choosing the example {EXAMPLE} fills the scene text with a contact scene")
    scene["bodies"][0]["material"]["poisson_ratio"] = 0.5
    del scene["time"]["step"]
    set_scene_and_submit(browser, scene)
    pointer = "/bodies/0/material/poisson_ratio"
    browser.wait_for(f"document.querySelector('[data-error-for=\"{pointer}\"]')", "the 422 errors are shown")
    field = browser.run(f"document.querySelector('[data-error-for=\"{pointer}\"]').parentElement.dataset.pointer")
    message = browser.run(f"document.querySelector('[data-error-for=\"{pointer}\"]').textContent")
    check(field == pointer, f"the error for {pointer} sits in the field {pointer} (got {field})")
    check("must be in (-1, 0.5), got 0.5" in message, f"its message names the rule: {message!r}")
    field = browser.run("document.querySelector('[data-error-for=\"/time/step\"]').parentElement.dataset.pointer")
    message = browser.run("document.querySelector('[data-error-for=\"/time/step\"]').textContent")
    check(field == "/time" and message == "step: required",
          f"a missing member is reported next to its object: {field} {message!r}")


def warnings_listed(browser):
    """A scene whose slave lies behind its master validates with a warning, listed as data under the form."""
    choose(browser, "example", EXAMPLE)
    scene = json.loads(browser.run("document.getElementById('scene-text').value"))
    scene["contact"][0]["master"] = "plate/bottom"
    browser.run(f"document.getElementById('scene-text').value = {js(json.dumps(scene, indent=2))}")
    browser.run("document.getElementById('validate-button').click()")
    browser.wait_for("document.querySelector('#scene-warnings li.warning')", "the validate warnings are listed")
    warning = browser.run("(() => { const w = document.querySelector('#scene-warnings li.warning');"
                          " return [w.dataset.code, w.dataset.pointer, w.textContent]; })()")
    check(warning[0] == "contact_behind_master" and warning[1] == "/contact/0/master",
          f"the warning has its code and pointer: {warning[:2]}")
    check("did you mean plate/top?" in warning[2], f"and its fix: {warning[2]!r}")
    outcome = browser.run("document.getElementById('submit-outcome').textContent")
    check(outcome.startswith("valid:") and "1 warning" in outcome, f"a scene with a warning is still valid: {outcome!r}")
    choice = browser.run("document.querySelector('#scene-warnings li.choice')?.textContent || ''")
    check(choice.startswith("/contact/0/master_surface: smooth"), f"the resolved master surface is listed: {choice!r}")
    schemes = browser.run("[...document.querySelectorAll('#study-schemes input')].map(b => b.value)")
    check(schemes == ["energy_momentum", "midpoint", "hht", "generalized_alpha"],
          f"the study form offers every dynamic scheme: {schemes}")


def decade_labels(browser, selector, what):
    """The axis labels under `selector` are distinct decades (1e-12, 0.01, 1, 100, …), or one-digit steps
    (1-2-5, then 1…9) where fewer than two decades fall inside; never 1.00e-11, 9.00e-13."""
    labels = browser.run(f"[...document.querySelectorAll({js(selector)})].map(l => l.textContent)")
    decade = re.compile(r"^([1-9]e-?\d+|0\.0*[1-9]|[1-9]0*)$")
    check(labels and all(decade.match(label) for label in labels) and len(set(labels)) == len(labels),
          f"{what}: decades (or one-digit steps) only, none repeated: {labels}")


def live_run(browser, out):
    choose(browser, "example", EXAMPLE)
    browser.run("document.getElementById('submit-button').click()")
    points = "Number((document.getElementById('plot-energy') || {dataset: {}}).dataset.points || 0)"
    status = "document.getElementById('job-status').textContent"
    browser.wait_for(f"{points} > 0", "the energy plot holds points")
    seen_running = []  # point counts sampled while the page says running
    verdicts_running = set()  # the verdict row of the summary "so far"
    screenshot_taken = contact_screenshot_taken = False
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        now_status, now_points = browser.run(f"[{status}, {points}]")
        if now_status != "running":
            break
        seen_running.append(now_points)
        verdicts_running.add(browser.run(VERDICT_SHOWN))
        if not screenshot_taken and now_points > 10:
            browser.screenshot(out / "running.png")
            screenshot_taken = True
        if not contact_screenshot_taken and now_points > 45:  # the ball hit the plate near step 32
            browser.screenshot(out / "running_contact.png")  # the README's picture
            contact_screenshot_taken = True
        time.sleep(0.1)
    check(len(set(seen_running)) >= 2 and seen_running[-1] > seen_running[0],
          f"the number of plotted points grows while the job runs (sampled {sorted(set(seen_running))})")
    browser.wait_for(f"{status} === 'succeeded'", "the status reaches succeeded")
    check(True, "the status reaches succeeded")
    browser.wait_for(f"{points} === {EXAMPLE_ROWS}", f"the energy plot ends with {EXAMPLE_ROWS} points", limit=20)
    plots = browser.run("[...document.querySelectorAll('#plots .plot')].map(p => [p.id, Number(p.dataset.points)])")
    expected = ["plot-energy", "plot-energy-error", "plot-momentum-error", "plot-contact", "plot-newton",
                "plot-contact-force"]
    check([p[0] for p in plots] == expected, f"the contact run has the plots {expected} (got {plots})")
    check(all(p[1] == EXAMPLE_ROWS for p in plots),
          f"every plot holds each of the {EXAMPLE_ROWS} steps exactly once, polled with ?since")
    decade_labels(browser, "#plot-energy-error .dygraph-axis-label-y", "the energy error's log axis")
    decade_labels(browser, "#plot-momentum-error .dygraph-axis-label-y", "the momentum error's log axis")
    xlabel = browser.run("document.querySelector('#plot-energy .dygraph-xlabel')?.textContent")
    check(xlabel == "t (model units)", f"the time axis names its units: {xlabel!r}")
    summary = browser.run("document.getElementById('job-summary').textContent")
    check("energy_drift" in summary and "max_penetration" in summary, "the summary shows energy drift and penetration")
    check("made when the run ends" in verdicts_running,
          f"while the job runs, its summary says the verdict is made when the run ends: {verdicts_running}")
    check(browser.run(VERDICT_SHOWN) == "ok", f"the finished job's summary shows the verdict ok: {browser.run(VERDICT_SHOWN)!r}")
    checks = browser.run("[...document.querySelectorAll('#job-summary th')].map(t => t.textContent)"
                         ".filter(t => t.startsWith('check '))")
    check("check energy_balance" in checks and "check penetration" in checks,
          f"the summary lists the named checks: {checks}")
    check(browser.run(status) == "succeeded", "an ok job is not marked suspect")
    log = browser.run("document.getElementById('job-log').textContent")
    check("run completed: 100 steps" in log, f"the log is shown: {log.strip().splitlines()[-1]!r}")
    download = browser.run("""(async () => {
        const link = document.getElementById('download-result');
        const response = await fetch(link.href);
        const bytes = new Uint8Array(await response.arrayBuffer());
        return {href: link.getAttribute('href'), status: response.status, size: bytes.length,
                head: [...bytes.slice(0, 8)]};
      })()""")
    check(download["status"] == 200 and download["head"] == HDF5_SIGNATURE and download["size"] > 10000,
          f"the download link {download['href']} serves an HDF5 file ({download['size']} bytes)")
    return browser.run("location.hash.slice(5)")


def job_list_filter(browser, job_id):
    def rows_for(status):
        choose(browser, "status-filter", status)
        browser.wait_for(f"[...document.querySelectorAll('#jobs tbody tr')].every(r => "
                         f"{js(status)} === '' || r.dataset.status === {js(status)})", f"the list filtered by {status}")
        return browser.run("[...document.querySelectorAll('#jobs tbody tr')].map(r => r.dataset.id)")

    check(job_id in rows_for("succeeded"), "the job is listed under status succeeded")
    check(job_id not in rows_for("failed"), "and not under status failed")
    rows_for("")


def study_view(browser, server, source_dir):
    scene = json.loads((source_dir / "api/examples/tumbling_bar.json").read_text())
    study = server.post("/v1/studies", {"scene": scene, "steps": [0.1, 0.05]})
    click_job_row(browser, study["id"])
    accuracy = "document.getElementById('plot-accuracy').dataset"
    browser.wait_for(f"{accuracy}.points === '6'", "the accuracy plot holds 3 schemes × 2 steps")
    check(browser.run(f"{accuracy}.lines") == "3", "the accuracy plot has one line per scheme")
    rows = browser.run("document.querySelectorAll('#study-table tr').length")
    check(rows == 7, f"the study table has a header and 6 rows (got {rows})")
    log_scales = browser.run("(() => { const g = document.querySelector('#plot-accuracy canvas'); return !!g; })()")
    check(log_scales, "the accuracy plot is drawn")
    x_labels = browser.run("[...document.querySelectorAll('#plot-accuracy .dygraph-axis-label-x')].map(l => l.textContent)")
    check(len(x_labels) >= 2, f"the study's wall-time axis has at least two labels: {x_labels}")
    decade_labels(browser, "#plot-accuracy .dygraph-axis-label-x", "the study's wall-time axis")
    decade_labels(browser, "#plot-accuracy .dygraph-axis-label-y", "the study's error axis")
    xlabel = browser.run("document.querySelector('#plot-accuracy .dygraph-xlabel')?.textContent")
    check(xlabel == "wall seconds (median of 3 runs)", f"the x axis says how wall time was measured: {xlabel!r}")
    browser.wait_for("document.querySelectorAll('#plot-accuracy .step-label').length === 6", "every point is labelled")
    steps = browser.run("[...document.querySelectorAll('#plot-accuracy .step-label')].map(a => a.textContent).sort()")
    check(steps == ["h=0.05"] * 3 + ["h=0.1"] * 3, f"each point is labelled with its h: {steps}")
    note = browser.run("document.getElementById('study-energy-note').textContent")
    check("2.0 and 2.3 H₀" in note and "6.3 and 7.2 H₀ on the holed_part_plate example" in note and "4v/h" in note,
          "the study page says how much and why HHT-α and generalized-α gain energy")
    timing = browser.run("document.getElementById('study-timing').textContent")
    check(timing == "wall seconds: the median of 3 runs of each scheme and step (wall time, not CPU time).",
          f"the study page says how it times the runs: {timing!r}")
    # Each row's wall time: the median of its 3 runs and their range, the runs themselves in the title.
    walls = browser.run("[...document.querySelectorAll('#study-table td.wall')].map(td => [td.textContent, td.title])")
    parsed = [re.fullmatch(r"([0-9.e+-]+) \(([0-9.e+-]+)–([0-9.e+-]+)\)", text) for text, _ in walls]
    check(len(walls) == 6 and all(parsed) and all(float(m[2]) <= float(m[1]) <= float(m[3]) for m in parsed)
          and all(title.startswith("3 runs: ") and title.count(",") == 2 for _, title in walls),
          f"each row shows its median wall time between its fastest and slowest of 3 runs: {walls[:2]}")


def adaptive_run(browser, server, source_dir):
    """A run with steps chosen by time.tolerance plots its step size against time (issue 22 §5), and its
    progress goes by simulated time: the finished job shows 100 %."""
    scene = json.loads((source_dir / "api/examples/tumbling_bar.json").read_text())
    scene["time"]["tolerance"] = 1e-3
    scene["output"] = {"every": 40}  # the server counts end/min_step steps: 41 frames at most, under --max-frames
    job = server.post("/v1/jobs", scene)
    click_job_row(browser, job["id"])
    browser.wait_for(f"document.getElementById('job-kind').textContent.includes({js(job['id'])}) &&"
                     " document.getElementById('job-status').textContent === 'succeeded'", "the adaptive run succeeds")
    with urllib.request.urlopen(f"{server.url}/v1/jobs/{job['id']}/series", timeout=30) as response:
        rows = len(json.load(response)["time"])
    points = "Number(document.getElementById('plot-step-size')?.dataset.points)"
    browser.wait_for(f"{points} === {rows}", f"the step-size plot holds the {rows} rows of the series", limit=20)
    plots = browser.run("[...document.querySelectorAll('#plots .plot')].map(p => p.id)")
    check("plot-step-size" in plots, f"the adaptive run has a step-size plot: {plots}")
    sizes = browser.run("shown.data['step-size'].map(r => r[1]).filter(v => v > 0)")
    spread = max(sizes) / min(sizes) if sizes else 0
    check(spread > 1.5, f"the {len(sizes)} plotted step sizes vary (max/min {spread:.3g})")
    progress = browser.run("document.getElementById('job-progress').textContent")
    check("(100 %)" in progress, f"the finished adaptive run's progress is 100 % of its time: {progress!r}")


def punch_run(browser, server, source_dir):
    """A flat punch pressed in by static load steps (api/examples/punch.json, issue 23 §6) is plotted with its
    external work, the reaction force of each boundary entry and the contact force: the punch's force against
    its displacement, the picture in docs/measurements.md."""
    scene = json.loads((source_dir / "api/examples/punch.json").read_text())
    job = server.post("/v1/jobs", scene)
    click_job_row(browser, job["id"])
    browser.wait_for(f"document.getElementById('job-kind').textContent.includes({js(job['id'])}) &&"
                     " document.getElementById('job-status').textContent === 'succeeded'", "the punch run succeeds")
    with urllib.request.urlopen(f"{server.url}/v1/jobs/{job['id']}/series", timeout=30) as response:
        series = json.load(response)
    rows = len(series["time"])
    for plot in ["external-work", "reaction-force", "contact-force"]:
        points = f"Number(document.getElementById('plot-{plot}')?.dataset.points)"
        browser.wait_for(f"{points} === {rows}", f"the {plot} plot holds the {rows} load levels", limit=20)
    # The last plotted row: [t, entry 0 x, y, z, entry 1 x, y, z] and [t, pair 0 x, y, z].
    reaction, contact = browser.run("[shown.data['reaction-force'].at(-1), shown.data['contact-force'].at(-1)]")
    force = series["contact_force"][-1][0][2]
    check(contact[3] == force and force < -1, f"the contact-force plot ends at the series' force {force} (got {contact[3]})")
    check(abs(reaction[6] - force) <= 1e-8 * abs(force),
          f"the punch top's plotted reaction {reaction[6]} equals the contact force {force}: the supports balance")
    work = browser.run("shown.data['external-work'].at(-1)")
    check(abs(work[1] - series["external_work"][-1]) == 0 and abs(work[2]) < 1e-3 * work[1],
          f"the external work W = {work[1]} is plotted, and H − W = {work[2]} is small beside it")
    plots = browser.run("[...document.querySelectorAll('#plots .plot')].map(p => p.id)")
    check("plot-energy-error" not in plots and "plot-momentum-error" not in plots,
          f"static load steps plot neither an energy nor a momentum error: {plots}")
    hidden = browser.run("[...document.querySelectorAll('#job-summary th')].map(t => t.textContent)"
                         ".filter(t => t.endsWith('_drift'))")
    check(hidden == [], f"nor list the energy or momentum drift in the summary table: {hidden}")
    browser.run("document.getElementById('plot-external-work').scrollIntoView()")


def tolerance_study_view(browser, binary, source_dir, work):
    """A study with tolerances plots them as a line of their own, each point labelled with its TOL. The table
    is a real one (`stoss study --tolerances --json`) served to the page in place of GET …/study."""
    scene = source_dir / "api/examples/tumbling_bar.json"
    table = json.loads(subprocess.run([binary, "study", str(scene), "--steps", "0.1,0.05", "--tolerances", "1e-3",
                                       "--schemes", "energy_momentum", "--repeat", "1", "--json"],
                                      check=True, capture_output=True, text=True).stdout)
    browser.run(f"""(() => {{ const table = {js(table)}; const real = window.fetch;
        window.fetch = (path, options) => path === '/stub/study'
          ? Promise.resolve(new Response(JSON.stringify(table), {{ status: 200, headers: {{ 'Content-Type': 'application/json' }} }}))
          : real(path, options);
        shown.studyShown = false;
        return showStudy({{ kind: 'study', status: 'succeeded', links: {{ study: '/stub/study' }} }}); }})()""")
    accuracy = "document.getElementById('plot-accuracy').dataset"
    browser.wait_for(f"{accuracy}.points === '3'", "the tolerance study's plot holds 2 steps and 1 tolerance")
    check(browser.run(f"{accuracy}.lines") == "2", "a line for the fixed steps and one for the tolerance")
    legend = browser.run("document.getElementById('accuracy-legend').textContent")
    check("adaptive energy_momentum" in legend, f"the tolerance's line is named adaptive energy_momentum: {legend!r}")
    browser.wait_for("document.querySelectorAll('#plot-accuracy .step-label').length === 3", "every point is labelled")
    labels = browser.run("[...document.querySelectorAll('#plot-accuracy .step-label')].map(a => a.textContent).sort()")
    check(labels == ["TOL=0.001", "h=0.05", "h=0.1"], f"the tolerance's point is labelled with its TOL: {labels}")
    head = browser.run("[...document.querySelectorAll('#study-table th')].map(t => t.textContent)")
    check("tolerance (model units)" in head, f"the table has a tolerance column: {head}")


def fits_1280(browser):
    """At 1280 px wide nothing in either column reaches past the column's right edge."""
    browser.call("Emulation.setDeviceMetricsOverride", width=1280, height=2400, deviceScaleFactor=1, mobile=False)
    time.sleep(0.5)
    overflowing = browser.run("""[...document.querySelectorAll('main > section')].filter(s => !s.hidden)
        .flatMap(s => [...s.querySelectorAll('*')].filter(e => e.offsetParent !== null &&
                 e.getBoundingClientRect().right > s.getBoundingClientRect().right + 1)
            .map(e => `${s.id} ${e.tagName.toLowerCase()}#${e.id}.${e.className}: right edge ` +
                      `${Math.round(e.getBoundingClientRect().right)} > ${Math.round(s.getBoundingClientRect().right)}`))""")
    check(overflowing == [], f"nothing reaches past its column at 1280 px: {overflowing[:6]}")
    browser.call("Emulation.clearDeviceMetricsOverride")


def token_prompt(browser, binary, work):
    (work / "token").write_text("browser-secret\n")
    server = Server(binary, work / "data-token", "--token-file", str(work / "token"))
    try:
        browser.run("sessionStorage.clear()")
        browser.open(server.url + "/")
        browser.wait_for("!document.getElementById('token-panel').hidden", "the page asks for the token")
        check(browser.run("document.querySelectorAll('#example option').length") == 1,
              "nothing is loaded before the token is given")
        browser.run("document.getElementById('token-input').value = 'browser-secret';"
                    "document.getElementById('token-form').requestSubmit()")
        browser.wait_for("document.querySelectorAll('#example option').length > 1",
                         "with the token the examples load")
        check(browser.run("sessionStorage.getItem('stoss-token')") == "browser-secret",
              "the token is kept in session storage")
    finally:
        server.stop()


def main():
    binary, build_dir = sys.argv[1], Path(sys.argv[2])
    source_dir = Path(__file__).resolve().parents[2]
    out = build_dir / "browser"
    out.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix="stoss-browser-"))
    server = browser = None
    try:
        server = Server(binary, work / "data")
        browser = Browser(work / "profile")
        browser.open(server.url + "/")
        browser.wait_for("document.querySelectorAll('#example option').length > 1", "the examples are listed")
        names = browser.run("[...document.querySelectorAll('#example option')].map(o => o.value)")
        check(EXAMPLE in names and "ball_plate_inp" not in names,
              "the bundled examples are offered, without those that need a mesh file")
        validation_errors_next_to_fields(browser)
        warnings_listed(browser)
        job_id = live_run(browser, out)
        job_list_filter(browser, job_id)
        click_job_row(browser, job_id)
        browser.wait_for(f"Number(document.getElementById('plot-energy')?.dataset.points) === {EXAMPLE_ROWS}",
                         "the finished job's plots come back when it is opened again")
        browser.screenshot(out / "page.png")
        study_view(browser, server, source_dir)
        browser.screenshot(out / "study.png")
        fits_1280(browser)  # the study on show (plots drawn at 1400 px keep their width when the window shrinks)
        adaptive_run(browser, server, source_dir)
        browser.screenshot(out / "adaptive.png")
        punch_run(browser, server, source_dir)
        browser.screenshot(out / "punch.png")  # docs/images/punch.png
        tolerance_study_view(browser, binary, source_dir, work)
        browser.screenshot(out / "study_tolerance.png")
        token_prompt(browser, binary, work)
    finally:
        if browser:
            browser.stop()
        if server:
            server.stop()
        shutil.rmtree(work, ignore_errors=True)
    print(f"{CHECKS['passed']} passed, {CHECKS['failed']} failed")
    return 1 if CHECKS["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
