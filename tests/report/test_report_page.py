"""The report page in a real browser: headless Chromium (Debian's chromium and chromium-driver)
driven by Selenium opens the page from a file URL with the network off and checks that it shows
what its JSON says: no console errors, a 3-D view that is drawn (not blank) and turns, every
number shown equal to the JSON value its data-source points at, the decimation stated, the
sections with their units, and the robot's bodies moving with the animation's frames.

The page: MCWS_REPORT_HTML (a report.html of mcws_study, say), else the synthetic report that
MCWS_WRITE_TEST_REPORT (tests/report/write_test_report) writes. Chromium and its driver:
MCWS_CHROMIUM, MCWS_CHROMEDRIVER (default /usr/bin/chromium, /usr/bin/chromedriver).
Run: python3 -m pytest -q tests/report/test_report_page.py
"""
import base64
import decimal
import io
import json
import math
import os
import struct
import subprocess
import tempfile
import time

import pytest
from PIL import Image, ImageChops, ImageStat
from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By

# A canvas showing the scene varies in brightness; a blank one (one background colour) does not.
# The grey-level variance of the synthetic scene's canvas is about 2 000; 20 leaves room for a
# sparser scene and stays far above a blank canvas's 0.
MIN_CANVAS_VARIANCE = 20.0
# Share of the canvas's pixels that must change when the view turns 60 degrees or a layer is
# hidden (the synthetic scene: 12 % and 3 %), and when the bodies go from the first frame to the
# last (1.5 %).
MIN_CHANGED_SHARE = 0.005
MIN_MOVED_SHARE = 0.001
# Chromium's flags: software WebGL (SwiftShader through ANGLE) in headless mode, nothing fetched
# from the network (no name resolves, every request goes to a closed port), a fresh profile.
CHROMIUM_FLAGS = [
    "--headless=new", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
    "--window-size=1280,1100", "--disable-background-networking", "--disable-component-update",
    "--disable-sync", "--no-first-run", "--disable-default-apps", "--disable-extensions",
    "--host-resolver-rules=MAP * ~NOTFOUND", "--proxy-server=127.0.0.1:9",
    "--proxy-bypass-list=<-loopback>", "--disable-dev-shm-usage",
]


def js_number_text(value):
    """What the page shows for a JSON value: JavaScript's String(Number(v.toPrecision(6))),
    worked out here from the exact decimal value (ECMAScript's rounding: half away from zero
    on the magnitude; its Number::toString layout)."""
    if value is None:
        return "n/a"
    if isinstance(value, bool):
        return "true" if value else "false"
    if not isinstance(value, (int, float)):
        return str(value)
    if value == 0:
        return "0"
    exact = decimal.Decimal(value)
    sign = "-" if exact < 0 else ""
    exact = abs(exact)
    exponent = exact.adjusted()
    mantissa = exact.scaleb(-exponent).quantize(decimal.Decimal("1.00000"),
                                                rounding=decimal.ROUND_HALF_UP)
    if mantissa >= 10:
        mantissa, exponent = decimal.Decimal("1.00000"), exponent + 1
    digits = str(mantissa).replace(".", "").rstrip("0")
    k, n = len(digits), exponent + 1
    if k <= n <= 21:
        text = digits + "0" * (n - k)
    elif 0 < n <= 21:
        text = digits[:n] + "." + digits[n:]
    elif -6 < n <= 0:
        text = "0." + "0" * -n + digits
    else:
        text = digits[0] + ("." + digits[1:] if k > 1 else "") + "e" + \
            ("+" if n - 1 >= 0 else "-") + str(abs(n - 1))
    return sign + text


# Hand-checked: what String(Number(v.toPrecision(6))) gives (ties to the larger magnitude,
# exponent form from 1e21 up and below 1e-6).
NUMBER_TEXTS = {-5.0: "-5", 0.0123456789: "0.0123457", 1234567.89: "1234570", 1.5e-7: "1.5e-7",
                0.987654321: "0.987654", 20: "20", 1e21: "1e+21", 1.234565e23: "1.23457e+23",
                0.000001: "0.000001", 2.5e-6: "0.0000025", -0.0: "0", 999999.5: "1000000",
                1234565: "1234570", -1234565: "-1234570", 0.1 + 0.2: "0.3"}


def test_js_number_text_follows_javascript():
    for value, text in NUMBER_TEXTS.items():
        assert js_number_text(value) == text, value


def test_page_formats_numbers_as_the_test_does(browser):
    values = list(NUMBER_TEXTS)
    shown = browser.execute_script("return arguments[0].map(mcws.formatNumber)", values)
    assert shown == [js_number_text(v) for v in values]


def resolve_pointer(document, pointer):
    """The value at an RFC 6901 JSON pointer (KeyError/IndexError when there is none)."""
    node = document
    for raw in pointer.split("/")[1:]:
        key = raw.replace("~1", "/").replace("~0", "~")
        node = node[int(key)] if isinstance(node, list) else node[key]
    return node


def embedded_json(html, element_id):
    start_tag = '<script type="application/json" id="%s">' % element_id
    start = html.index(start_tag) + len(start_tag)
    return json.loads(html[start:html.index("</script>", start)])


def floats(text):
    data = base64.b64decode(text)
    return struct.unpack("<%df" % (len(data) // 4), data)


@pytest.fixture(scope="module")
def page_path(tmp_path_factory):
    given = os.environ.get("MCWS_REPORT_HTML")
    if given:
        return os.path.abspath(given)
    writer = os.environ.get("MCWS_WRITE_TEST_REPORT")
    if not writer:
        pytest.fail("set MCWS_REPORT_HTML (a page) or MCWS_WRITE_TEST_REPORT (the writer)")
    path = str(tmp_path_factory.mktemp("report") / "report.html")
    # 2 000 boundary points under a 20 000-byte limit: the page keeps every 2nd (1 000).
    subprocess.run([writer, path, "2000", "20000"], check=True)
    return path


@pytest.fixture(scope="module")
def page_json(page_path):
    with open(page_path, encoding="utf-8") as f:
        html = f.read()
    return embedded_json(html, "mcws-report"), embedded_json(html, "mcws-scene")


@pytest.fixture(scope="module")
def browser(page_path):
    options = webdriver.ChromeOptions()
    options.binary_location = os.environ.get("MCWS_CHROMIUM", "/usr/bin/chromium")
    profile = tempfile.TemporaryDirectory(prefix="mcws-chromium-")
    for flag in CHROMIUM_FLAGS + ["--user-data-dir=" + profile.name]:
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    service = Service(os.environ.get("MCWS_CHROMEDRIVER", "/usr/bin/chromedriver"))
    driver = webdriver.Chrome(service=service, options=options)
    try:
        driver.execute_cdp_cmd("Network.enable", {})
        driver.execute_cdp_cmd("Network.emulateNetworkConditions", {
            "offline": True, "latency": 0, "downloadThroughput": 0, "uploadThroughput": 0})
        start = time.monotonic()
        driver.get("file://" + page_path)
        while not driver.execute_script("return !!(window.mcwsReport && (window.mcwsReport.ready "
                                        "|| window.mcwsReport.error))"):
            assert time.monotonic() - start < 30, "the page did not get ready in 30 s"
            time.sleep(0.02)
        driver.mcws_open_seconds = time.monotonic() - start
        yield driver
    finally:
        driver.quit()
        profile.cleanup()


@pytest.fixture(scope="module")
def webgl(browser):
    if not browser.execute_script("return window.mcwsReport.webgl"):
        pytest.skip("this headless Chromium gives no WebGL: the canvas checks cannot run")
    return browser


def canvas_image(driver):
    """The canvas's pixels, without its CSS border (which alone would not be blank)."""
    png = driver.find_element(By.ID, "scene-canvas").screenshot_as_png
    image = Image.open(io.BytesIO(png)).convert("RGB")
    return image.crop((3, 3, image.width - 3, image.height - 3))


def changed_share(before, after):
    difference = ImageChops.difference(before, after).convert("L").point(lambda v: 255 if v > 8 else 0)
    return ImageStat.Stat(difference).mean[0] / 255


def test_page_gets_ready_without_console_errors_or_requests(browser):
    hook_error = browser.execute_script("return window.mcwsReport.error")
    assert hook_error is None, hook_error
    assert browser.execute_script("return window.mcwsReport.ready")
    errors = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
    assert errors == []
    fetched = browser.execute_script(
        "return performance.getEntriesByType('resource').map(e => e.name)"
        ".filter(n => !n.startsWith('data:'))")
    assert fetched == []
    print("page ready %.2f s after the request; since the navigation started: first text %.0f ms, "
          "3-D view drawn %.0f ms" % (browser.mcws_open_seconds, browser.execute_script(
              "return performance.getEntriesByName('first-contentful-paint')[0].startTime"),
              browser.execute_script("return window.mcwsReport.readyMs")))


def test_every_number_shown_equals_the_json_value_at_its_source(browser, page_json):
    report, _ = page_json
    shown = browser.execute_script(
        "return Array.from(document.querySelectorAll('[data-source]'))"
        ".map(e => [e.getAttribute('data-source'), e.textContent])")
    answers = report.get("view", {}).get("answers", [])
    sources = {pointer for pointer, _ in shown}
    for i, answer in enumerate(answers):
        assert answer.get("source", "/view/answers/%d/value" % i) in sources, answer
    assert len(shown) >= len(answers)
    for pointer, text in shown:
        assert text == js_number_text(resolve_pointer(report, pointer)), pointer


def test_sections_show_titles_and_units(browser, page_json):
    report, _ = page_json
    sections = report.get("view", {}).get("sections", [])
    titles = [e.text for e in browser.find_elements(By.CSS_SELECTOR, "#sections > section > h2")]
    assert titles == [s.get("title", "") for s in sections]
    text = browser.find_element(By.ID, "sections").get_attribute("textContent")
    for section in sections:
        if section["kind"] == "table":
            for column in section["columns"]:
                unit = column.get("unit")
                assert column["name"] + (" [%s]" % unit if unit else "") in text
        elif section["kind"] == "chart":
            for axis in (section["x"], section["y"]):
                assert "%s [%s]" % (axis["label"], axis["unit"]) in text
        elif section["kind"] == "timeline":
            assert "time [%s]" % section["unit"] in text
            for lane in section["lanes"]:
                assert lane in text


def test_decimated_layers_are_stated(browser, page_json):
    _, scene = page_json
    note = browser.find_element(By.ID, "decimation").text
    for layer in scene["layers"]:
        if layer["points"] < layer["total_points"]:
            grouped = lambda n: "{:,}".format(n).replace(",", "\u202f")
            assert "%s: %s of %s shown" % (layer["name"], grouped(layer["points"]),
                                           grouped(layer["total_points"])) in note


def test_canvas_is_drawn_and_turns_with_the_view(webgl):
    before = canvas_image(webgl)
    variance = ImageStat.Stat(before.convert("L")).var[0]
    assert variance > MIN_CANVAS_VARIANCE, "the canvas looks blank (variance %.1f)" % variance
    webgl.execute_script("window.mcwsReport.rotate(60)")
    after = canvas_image(webgl)
    assert changed_share(before, after) > MIN_CHANGED_SHARE
    webgl.execute_script("window.mcwsReport.rotate(-60)")


def test_layer_checkbox_hides_its_layer(webgl, page_json):
    _, scene = page_json
    visible = [layer["name"] for layer in scene["layers"] if layer["visible"] and layer["points"]]
    if not visible:
        pytest.skip("no visible layer to hide")
    before = canvas_image(webgl)
    box = webgl.find_element(By.CSS_SELECTOR, 'input[data-layer="%s"]' % visible[0])
    box.click()
    after = canvas_image(webgl)
    box.click()
    assert changed_share(before, after) > MIN_CHANGED_SHARE


def test_animation_frames_move_the_bodies_where_the_poses_say(browser, page_json):
    _, scene = page_json
    if not scene["animations"] or not scene["bodies"]:
        pytest.skip("the page has no animation of the bodies")
    animation = scene["animations"][0]
    poses, bodies, last = floats(animation["poses"]), len(scene["bodies"]), animation["frames"] - 1
    moved = 0.0
    for i in range(bodies):
        start = browser.execute_script("window.mcwsReport.setFrame(0); return window.mcwsReport.bodyPosition(%d)" % i)
        end = browser.execute_script("window.mcwsReport.setFrame(%d); return window.mcwsReport.bodyPosition(%d)" % (last, i))
        for frame, shown in ((0, start), (last, end)):
            expected = poses[(frame * bodies + i) * 16 + 12:(frame * bodies + i) * 16 + 15]
            assert shown == pytest.approx(expected, rel=1e-6, abs=1e-6)
        moved = max(moved, math.dist(start, end))
    assert moved > 0, "no body moves between the first and the last frame"
    frame_text = browser.find_element(By.ID, "animation-frame").text
    assert "frame %d of %d" % (last + 1, animation["frames"]) in frame_text
    if animation["parameter_unit"]:
        assert animation["parameter_unit"] in frame_text
    if browser.execute_script("return window.mcwsReport.webgl"):
        last_image = canvas_image(browser)
        browser.execute_script("window.mcwsReport.setFrame(0)")
        assert changed_share(canvas_image(browser), last_image) > MIN_MOVED_SHARE
    browser.execute_script("window.mcwsReport.setFrame(0)")
