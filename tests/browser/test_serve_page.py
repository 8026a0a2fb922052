"""The serve page in a real browser (headless Debian chromium driven by chromedriver through selenium)
against `mocapdb serve` on a database made here from the shared CMU data: the clip list, a skeleton
that renders and moves, the packed view's max error against `pack`'s own measurement, a slider that
changes the synthesized motion with the rho `mocapdb query` gives, and a console without errors.
Screenshots of each view go to the build folder (--screenshots)."""
import json
import re
import shutil
import subprocess
import time
from pathlib import Path

import pytest

webdriver = pytest.importorskip("selenium.webdriver")

WALKS = [f"16_{t}" for t in range(11, 17)]


def run(cli, *args):
    out = subprocess.run([cli, *map(str, args)], capture_output=True, text=True, check=False)
    assert out.returncode == 0, f"mocapdb {' '.join(map(str, args))}: {out.stderr}"
    return out.stdout


@pytest.fixture(scope="module")
def database(request, tmp_path_factory):
    cli, shared = request.config.getoption("--cli"), Path(request.config.getoption("--shared"))
    source = shared / "datasets" / "cmu-asfamc"
    if not source.exists():
        pytest.skip(f"shared data not found at {source}")
    folder = tmp_path_factory.mktemp("serve_page")
    for name in ["16.asf"] + [w + ".amc" for w in WALKS]:
        shutil.copy(source / name, folder / name)
    db = folder / "walks.h5"
    run(cli, "import", folder, "-o", db)
    run(cli, "set", "create", db, "--name", "walks", "--clips", "16_*", "--segment", "none", "--extract", "turn", "speed")
    run(cli, "align", db, "--set", "walks", "--frames", "30")
    run(cli, "compress", db, "--set", "walks", "--max-error-cm", "1")
    packed = json.loads(run(cli, "pack", db, "--max-error-cm", "1", "--json"))
    return cli, db, packed


@pytest.fixture(scope="module")
def server(database):
    cli, db, _ = database
    process = subprocess.Popen([cli, "serve", str(db), "--port", "0"], stdout=subprocess.PIPE, text=True)
    line = process.stdout.readline()
    url = re.search(r"http://\S+/", line)
    assert url, f"serve printed: {line!r}"
    yield url.group(0)
    process.send_signal(2)  # SIGINT: a clean stop
    assert process.wait(timeout=30) == 0
    assert "stopped" in process.stdout.read()


@pytest.fixture(scope="module")
def browser():
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for flag in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--window-size=1200,800",
                 "--use-angle=swiftshader", "--enable-unsafe-swiftshader"):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    service = webdriver.ChromeService(executable_path="/usr/bin/chromedriver") if hasattr(webdriver, "ChromeService") \
        else webdriver.chrome.service.Service("/usr/bin/chromedriver")
    driver = webdriver.Chrome(service=service, options=options)
    yield driver
    driver.quit()


def wait_for(driver, script, timeout=60):
    end = time.time() + timeout
    while time.time() < end:
        value = driver.execute_script(script)
        if value:
            return value
        time.sleep(0.1)
    raise AssertionError(f"timed out waiting for: {script}; page errors: "
                         f"{driver.execute_script('return window.mocapdbState && mocapdbState.errors')}")


PIXELS = """
const gl = document.querySelector('#view3d canvas');
const c = document.createElement('canvas'); c.width = gl.width; c.height = gl.height;
const g = c.getContext('2d'); g.drawImage(gl, 0, 0);
const d = g.getImageData(0, 0, c.width, c.height).data;
let drawn = 0, hash = 0;
for (let i = 0; i < d.length; i += 4) {
  if (Math.abs(d[i] - 0xf4) + Math.abs(d[i + 1] - 0xf4) + Math.abs(d[i + 2] - 0xf2) > 30) drawn++;
  hash = (hash * 31 + d[i] + 7 * d[i + 1] + 13 * d[i + 2]) | 0;
}
return [drawn, hash];
"""


def click_clip(driver, clip):
    # In the page's own script: the list is rebuilt on every choice, so a located element may be stale.
    driver.execute_script(f"document.querySelector(\"#clip-list li[data-id='{clip}']\").click()")


def show_frame(driver, frame):
    driver.execute_script(f"mocapdbState.playing = false; const s = document.getElementById('scrub');"
                          f"s.value = {frame}; s.dispatchEvent(new Event('input'));")
    time.sleep(0.3)  # a few animation frames


def test_clip_list_and_playback(server, browser, request):
    browser.get(server)
    wait_for(browser, "return document.querySelectorAll('#clip-list li').length")
    assert [li.get_attribute("data-id") for li in browser.find_elements("css selector", "#clip-list li")] == WALKS
    click_clip(browser, "16_13")
    wait_for(browser, "return mocapdbState.clip === '16_13' && mocapdbState.frames > 60")
    show_frame(browser, 0)
    drawn0, hash0 = browser.execute_script(PIXELS)
    show_frame(browser, 60)
    drawn1, hash1 = browser.execute_script(PIXELS)
    assert drawn0 > 200 and drawn1 > 200, "the skeleton is not drawn"
    assert hash0 != hash1, "the picture does not change between frames 0 and 60"
    browser.save_screenshot(str(Path(request.config.getoption("--screenshots")) / "serve_clips.png"))


def test_packed_view_shows_packs_max_error(server, database, browser, request):
    _, _, packed = database
    browser.get(server)
    wait_for(browser, "return document.querySelectorAll('#clip-list li').length")
    browser.find_element("css selector", "nav button[data-view='packed']").click()
    shown = []
    for clip in WALKS:
        click_clip(browser, clip)
        # The state and the shown figure in one script: the page redraws #info on every answer.
        text = wait_for(browser, f"return mocapdbState.packed && mocapdbState.packed.clip === '{clip}' && "
                                 "document.getElementById('packed-max').textContent")
        shown.append(float(text))
        assert browser.execute_script("return mocapdbState.packed.max_cm") <= 1.0 + 1e-4
    # The page's per-clip maxima: their largest is the tier's max measured by `pack` (4 decimals shown).
    assert max(shown) == pytest.approx(packed["max_cm"], abs=1e-4)
    browser.save_screenshot(str(Path(request.config.getoption("--screenshots")) / "serve_packed.png"))


def test_slider_changes_the_synthesis_with_querys_rho(server, database, browser, request):
    cli, db, _ = database
    browser.get(server)
    browser.find_element("css selector", "nav button[data-view='sets']").click()
    first = wait_for(browser, "return mocapdbState.synth")
    browser.execute_script("const s = document.querySelector(\"#sliders input[data-param='speed']\");"
                           "s.value = Number(s.value) + 0.2 * (Number(s.max) - Number(s.min));"
                           "s.dispatchEvent(new Event('input'));")
    second = wait_for(browser, f"return mocapdbState.synth && mocapdbState.synth.c[1] !== {first['c'][1]} && mocapdbState.synth")
    assert second["checksum"] != first["checksum"], "the joint positions did not change"
    c = ",".join(repr(v) for v in second["c"])
    query = json.loads(run(cli, "query", db, "--set", "walks", "--param", c, "--frame", "0", "--json"))
    assert second["reliability"] == pytest.approx(query["reliability"], rel=1e-9)
    assert float(browser.find_element("id", "rho").text) == pytest.approx(query["reliability"], abs=1e-4)
    browser.save_screenshot(str(Path(request.config.getoption("--screenshots")) / "serve_sets.png"))


GLTF_IN_THREE = """
const done = arguments[arguments.length - 1];
(async () => {
  const buffer = await (await fetch('/api/clip.glb?id=16_12')).arrayBuffer();
  const gltf = await new Promise((ok, fail) => new THREE.GLTFLoader().parse(buffer, '', ok, fail));
  const motion = await (await fetch('/api/clip?id=16_12&end=100')).arrayBuffer();
  const n = new DataView(motion).getUint32(0, true);
  const header = JSON.parse(new TextDecoder().decode(new Uint8Array(motion, 4, n)));
  const floats = new Float32Array(motion, 4 + n + ((4 - (n % 4)) % 4));
  const mixer = new THREE.AnimationMixer(gltf.scene);
  mixer.clipAction(gltf.animations[0]).play();
  let worst = 0;
  for (const frame of [0, 37, 99]) {
    mixer.setTime(frame / header.frame_rate);
    gltf.scene.updateMatrixWorld(true);
    header.joints.forEach((j, k) => {
      const node = gltf.scene.getObjectByName(j.name === 'root' ? 'root_joint' : j.name);  // gltf_node_name
      const p = new THREE.Vector3().setFromMatrixPosition(node.matrixWorld).multiplyScalar(100);
      const q = floats.subarray(3 * (frame * header.joints.length + k), 3 * (frame * header.joints.length + k) + 3);
      worst = Math.max(worst, Math.hypot(p.x - q[0], p.y - q[1], p.z - q[2]));
    });
  }
  return { animations: gltf.animations.length, tracks: gltf.animations[0].tracks.length, worst };
})().then(done, (e) => done({ error: String(e) }));
"""


def test_gltf_download_plays_in_three_js(server, browser):
    """The clip's glTF, as the page's download link gives it, loaded by three.js's own GLTFLoader (from
    Debian's libjs-three) and played by its AnimationMixer: joints where our FK puts them."""
    browser.get(server)
    wait_for(browser, "return document.querySelectorAll('#clip-list li').length")
    loader = Path("/usr/share/javascript/three/examples/js/loaders/GLTFLoader.js")
    if not loader.exists():
        pytest.skip(f"{loader} not found (Debian libjs-three)")
    browser.execute_script(loader.read_text())
    browser.set_script_timeout(60)
    result = browser.execute_async_script(GLTF_IN_THREE)
    assert "error" not in result, result
    assert result["animations"] == 1 and result["tracks"] > 10
    assert result["worst"] < 1e-2, result  # cm, float32 on the way (the assimp test checks 1e-3 cm)


def test_packed_in_memory_at_a_chosen_error(server, browser):
    browser.get(server)
    wait_for(browser, "return document.querySelectorAll('#clip-list li').length")
    browser.find_element("css selector", "nav button[data-view='packed']").click()
    browser.execute_script("const s = document.getElementById('packed-e'); s.value = '0.1'; s.dispatchEvent(new Event('change'));")
    wait_for(browser, "return mocapdbState.packed && mocapdbState.packed.bound === 0.1")
    assert 0.0 < browser.execute_script("return mocapdbState.packed.max_cm") <= 0.1 + 1e-4


def test_no_console_errors(server, browser):
    browser.get(server)
    wait_for(browser, "return document.querySelectorAll('#clip-list li').length")
    time.sleep(1)
    severe = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
    assert not severe, severe
    assert browser.execute_script("return mocapdbState.errors") == []

