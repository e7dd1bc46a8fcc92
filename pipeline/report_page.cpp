#include "pipeline/report_page.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/html.h"
#include "core/shot.h"
#include "pipeline/process.h"
#include "pipeline/run_metrics.h"
#include "pipeline/stage_cache.h"

namespace shatter {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

const std::vector<ViewerFile> kViewerFiles = {
    {"build/three.min.js", "three.min.js"},
    {"examples/js/loaders/GLTFLoader.js", "GLTFLoader.js"},
    {"examples/js/controls/OrbitControls.js", "OrbitControls.js"},
    {"LICENSE", "three.LICENSE.txt"},
};
const char* const kViewerVersion = "0.147.0";

std::optional<std::string> find_viewer(std::string* why) {
    std::vector<fs::path> candidates;
    if (const char* env = std::getenv("SHATTER_NODE_MODULES")) {
        candidates.push_back(fs::path(env) / "three");
    } else {
        try {
            candidates.push_back(fs::path(own_executable()).parent_path().parent_path() / "node_modules" / "three");
        } catch (const Error&) {
        }
        if (const char* home = std::getenv("HOME")) candidates.push_back(fs::path(home) / ".cache/shatter/node/node_modules/three");
    }
    std::string looked;
    for (const fs::path& dir : candidates) {
        looked += (looked.empty() ? "" : ", ") + dir.string();
        std::error_code ec;
        bool complete = true;
        for (const ViewerFile& f : kViewerFiles) complete = complete && fs::is_regular_file(dir / f.package_path, ec);
        if (!complete || !fs::is_regular_file(dir / "package.json", ec)) continue;
        try {
            const auto package = nlohmann::json::parse(read_file((dir / "package.json").string(), "package.json"));
            if (package.value("version", "") == kViewerVersion) return dir.string();
        } catch (const std::exception&) {
        }
    }
    if (why) *why = looked;
    return std::nullopt;
}

namespace {

// A number, flag or null of summary.json as the page shows it.
std::string show_value(const json& v, const char* unit) {
    std::string text;
    if (v.is_null()) return "-";
    if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
    if (v.is_number_integer() || v.is_number_unsigned()) text = v.dump();
    else if (v.is_number_float()) text = fmt::format("{:.4g}", v.get<double>());
    else if (v.is_string()) text = v.get<std::string>();
    else text = v.dump();
    return *unit ? text + " " + unit : text;
}

// A table row of one value of summary.json, at a JSON pointer; data-key and data-value carry the
// pointer and the exact JSON value for tests.
std::string summary_row(const json& summary, const char* label, const char* pointer, const char* unit,
                        const char* note = "") {
    const json::json_pointer p(pointer);
    const json v = summary.contains(p) ? summary.at(p) : json(nullptr);
    return fmt::format("<tr><th>{}</th><td class=\"num\" data-key=\"{}\" data-value=\"{}\">{}</td><td class=\"muted\">{}</td></tr>\n",
                       html_escape(label), html_escape(pointer), html_escape(v.dump()), html_escape(show_value(v, unit)),
                       html_escape(note));
}

std::string setting_text(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

const char* const kTimesScript = R"JS(
(function () {
  'use strict';
  var body = document.querySelector('#times tbody');
  var times = window.shatterStageTimes;
  if (!Array.isArray(times)) {
    body.innerHTML = '<tr><td colspan="3" class="muted">report.times.js is missing: no stage times.</td></tr>';
    return;
  }
  times.forEach(function (s) {
    var row = document.createElement('tr');
    var last = s.last_ran_s === null ? '-' : s.last_ran_s.toFixed(2) + ' s';
    [s.stage, s.outcome + ' (' + s.seconds.toFixed(2) + ' s)', last].forEach(function (text, i) {
      var cell = document.createElement(i === 0 ? 'th' : 'td');
      if (i > 0) cell.className = 'num';
      cell.textContent = text;
      row.appendChild(cell);
    });
    body.appendChild(row);
  });
})();
)JS";

// The 3D view: three.js (classic scripts from viewer/), the .glb from the page's base64, its first
// animation on a loop, seen through the movie's camera (the .glb's node "camera", which the
// animation moves as render's camera moves) until the view is orbited, panned or zoomed; the
// "Movie camera" button goes back to it. window.shatterViewer is what tests drive: loaded, error,
// duration, pieces, setTime(t) (pauses), play(), pause(), camera() (the view's position, the
// direction it looks in, and whether it is the movie's), movieCamera().
const char* const kViewerScript = R"JS(
(function () {
  'use strict';
  var api = window.shatterViewer = { loaded: false, error: null, duration: 0, pieces: 0 };
  var box = document.getElementById('viewer');
  var status = document.getElementById('viewer-status');
  var slider = document.getElementById('scrub');
  var label = document.getElementById('time');
  var button = document.getElementById('play');
  var back = document.getElementById('movie-camera');
  function fail(message) { api.error = message; status.textContent = message; status.className = 'note'; }
  if (!window.THREE || !THREE.GLTFLoader || !THREE.OrbitControls) {
    fail('three.js did not load from viewer/: no 3D view.');
    return;
  }
  var text = document.getElementById('glb').textContent.replace(/\s+/g, '');
  var raw = atob(text), bytes = new Uint8Array(raw.length);
  for (var i = 0; i < raw.length; ++i) bytes[i] = raw.charCodeAt(i);
  var renderer;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (e) {
    fail('This browser has no WebGL: no 3D view (' + e.message + ').');
    return;
  }
  renderer.outputEncoding = THREE.sRGBEncoding;
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(0xe9ebef);
  var scene = new THREE.Scene();
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8d8d8d, 0.9));
  var sun = new THREE.DirectionalLight(0xffffff, 0.8);
  sun.position.set(1.5, 3, 2);
  scene.add(sun);
  var camera = new THREE.PerspectiveCamera(35, 16 / 9, 0.01, 1000);
  var controls = new THREE.OrbitControls(camera, renderer.domElement);
  var mixer = null, playing = false, last = 0, root = null;
  var movie = null, following = false;  // the .glb's camera; whether the view is it
  function render() { renderer.render(scene, camera); }
  function show(t) { slider.value = t; label.textContent = t.toFixed(2) + ' s'; }
  // The view takes the movie camera's place and vertical field of view (its own aspect).
  function follow() {
    root.updateMatrixWorld(true);
    camera.position.setFromMatrixPosition(movie.matrixWorld);
    camera.quaternion.setFromRotationMatrix(movie.matrixWorld);
    if (camera.fov !== movie.fov) {
      camera.fov = movie.fov;
      camera.updateProjectionMatrix();
    }
  }
  function setFollowing(on) {
    following = on && !!movie;
    back.disabled = following || !movie;
  }
  function setTime(t) {
    t = Math.max(0, Math.min(api.duration, t));
    // The clip loops: its own duration would wrap to the first frame, so the end is shown from
    // just before it (the last key's pose).
    mixer.setTime(Math.min(t, api.duration * (1 - 1e-7)));
    if (following) follow();
    show(t);
    render();
  }
  function tick(now) {
    if (!playing) return;
    var t = mixer.time + (now - last) / 1000;
    last = now;
    setTime(t > api.duration ? 0 : t);
    requestAnimationFrame(tick);
  }
  function play() {
    if (!mixer || playing) return;
    playing = true;
    button.textContent = 'Pause';
    last = performance.now();
    requestAnimationFrame(tick);
  }
  function pause() { playing = false; button.textContent = 'Play'; }
  function resize() {
    var w = box.clientWidth || 640, h = box.clientHeight || 360;
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    render();
  }
  new THREE.GLTFLoader().parse(bytes.buffer, '', function (gltf) {
    scene.add(gltf.scene);
    root = gltf.scene;
    gltf.scene.traverse(function (o) { if (o.isCamera && !movie) movie = o; });
    mixer = new THREE.AnimationMixer(gltf.scene);
    if (gltf.animations.length > 0) {
      mixer.clipAction(gltf.animations[0]).play();
      api.duration = gltf.animations[0].duration;
    }
    slider.max = api.duration;
    var bounds = new THREE.Box3();
    for (var k = 0; k <= 20; ++k) {
      mixer.setTime(api.duration * Math.min(k / 20, 1 - 1e-7));
      gltf.scene.updateMatrixWorld(true);
      bounds.expandByObject(gltf.scene);
    }
    mixer.setTime(0);
    var center = bounds.getCenter(new THREE.Vector3());
    var radius = bounds.getSize(new THREE.Vector3()).length() / 2 || 1;
    var grid = new THREE.GridHelper(radius * 4, 20, 0x9aa0aa, 0xc8ccd2);
    grid.position.y = bounds.min.y;
    scene.add(grid);
    camera.near = radius / 100;
    camera.far = radius * 100;
    camera.fov = parseFloat(box.dataset.fov) || 35;
    camera.updateProjectionMatrix();
    if (movie) {
      setFollowing(true);
      follow();
    } else {
      // far enough that the sphere around everything the animation reaches fits the view's height
      var distance = 1.15 * radius / Math.sin(camera.fov * Math.PI / 360);
      camera.position.copy(new THREE.Vector3(1.4, 0.9, 2.2).normalize().multiplyScalar(distance).add(center));
      controls.target.copy(center);
      controls.update();
    }
    // Moving the view leaves the movie's camera: the orbit turns about the point ahead of the view
    // nearest the pieces' centre as they are now.
    controls.addEventListener('start', function () {
      if (!following) return;
      setFollowing(false);
      var ahead = camera.getWorldDirection(new THREE.Vector3());
      var now = new THREE.Box3().setFromObject(root).getCenter(new THREE.Vector3());
      var d = Math.max(now.sub(camera.position).dot(ahead), radius / 100);
      controls.target.copy(camera.position).addScaledVector(ahead, d);
    });
    back.addEventListener('click', function () {
      setFollowing(true);
      follow();
      render();
    });
    var names = new Set();
    gltf.scene.traverse(function (o) { if (/^piece_\d+$/.test(o.name)) names.add(o.name); });
    api.pieces = names.size;
    status.style.display = 'none';
    box.appendChild(renderer.domElement);
    resize();
    window.addEventListener('resize', resize);
    controls.addEventListener('change', function () { if (!playing) render(); });
    slider.addEventListener('input', function () { pause(); setTime(parseFloat(slider.value)); });
    button.addEventListener('click', function () { if (playing) pause(); else play(); });
    button.disabled = false;
    slider.disabled = false;
    api.setTime = function (t) { pause(); setTime(t); };
    api.camera = function () {
      return { position: camera.position.toArray(), direction: camera.getWorldDirection(new THREE.Vector3()).toArray(),
               fov: camera.fov, following: following };
    };
    api.movieCamera = function () { back.click(); };
    api.play = play;
    api.pause = pause;
    api.loaded = true;
    play();
  }, function (e) {
    fail('The .glb could not be read: ' + (e && e.message ? e.message : e));
  });
})();
)JS";

std::string media_section(const json& files, const std::string& name) {
    auto has = [&](const char* key) { return files.contains(key); };
    std::string out = "<h2>Movie, contact sheet, energy</h2>\n<div class=\"grid\">\n";
    if (has("mp4"))
        out += fmt::format("<figure><video controls loop muted preload=\"metadata\" src=\"{}\"></video><figcaption>{}"
                           "</figcaption></figure>\n", url_path(files["mp4"].get<std::string>()),
                           html_escape(files["mp4"].get<std::string>()));
    else
        out += "<p class=\"note\">No movie: the encode stage did not make " + html_escape(name) + ".mp4 (run.log says why).</p>\n";
    for (const auto& [key, what] : {std::pair<const char*, const char*>{"contact.png", "contact sheet"}, {"energy.png", "energy plot"}}) {
        if (has(key))
            out += fmt::format("<figure><a href=\"{0}\"><img src=\"{0}\" alt=\"{1}\"></a><figcaption>{1}: {2}</figcaption></figure>\n",
                               url_path(files[key].get<std::string>()), what, html_escape(files[key].get<std::string>()));
        else
            out += fmt::format("<p class=\"note\">No {}: {}.{} was not made (run.log says why).</p>\n", what,
                               html_escape(name), key);
    }
    return out + "</div>\n";
}

std::string viewer_section(const ReportPageInput& in) {
    std::string out = "<h2>3D view</h2>\n";
    const json& files = in.summary["files"];
    if (in.glb.empty()) {
        return out + "<p class=\"note\">No 3D view: the export stage did not make " + html_escape(in.name) +
               ".glb (run.log says why).</p>\n";
    }
    if (!in.viewer) {
        return out + "<p class=\"note\" id=\"viewer-missing\">No 3D view: three.js " + kViewerVersion +
               " (the npm package <code>three</code>) was not found beside shatter (looked in " +
               html_escape(in.viewer_missing) +
               "). Install it with <code>bash scripts/install-node-tools.sh BUILD_DIR</code> and run again; "
               "meanwhile <a href=\"" + url_path(files.value("glb", in.name + ".glb")) + "\">" +
               html_escape(in.name) + ".glb</a> opens in Blender or any glTF viewer.</p>\n";
    }
    // The shot's field of view, for a .glb without the movie's camera.
    const json render = in.settings.value("render", json::object());
    const std::string camera = " data-fov=\"" + html_escape(render.value("fov", json(35.0)).dump()) + "\"";
    out += "<div class=\"viewer\" id=\"viewer\"" + camera + "><p id=\"viewer-status\" class=\"muted\">Loading " +
           html_escape(in.name) + ".glb&hellip;</p></div>\n";
    out += "<div class=\"controls\"><button id=\"play\" disabled>Play</button><input type=\"range\" id=\"scrub\" min=\"0\" "
           "max=\"1\" step=\"any\" value=\"0\" disabled><span id=\"time\">0.00 s</span>"
           "<button id=\"movie-camera\" disabled>Movie camera</button></div>\n";
    out += "<p class=\"muted\">Seen as the movie sees it; drag to orbit, right-drag to pan, wheel to zoom (Movie "
           "camera goes back); the slider scrubs the animation. "
           "The same animation: <a href=\"" + url_path(files.value("glb", in.name + ".glb")) + "\">" + html_escape(in.name) +
           ".glb</a>.</p>\n";
    // The .glb, embedded: a file:// page may not fetch() its neighbours.
    out += "<script id=\"glb\" type=\"application/octet-stream\">\n";
    const std::string b64 = base64(in.glb);
    for (size_t i = 0; i < b64.size(); i += 120) out += b64.substr(i, 120) + "\n";
    out += "</script>\n";
    for (const ViewerFile& f : kViewerFiles)
        if (std::string(f.name).size() > 3 && std::string(f.name).substr(std::string(f.name).size() - 3) == ".js")
            out += fmt::format("<script src=\"viewer/{}\"></script>\n", f.name);
    out += "<script>" + std::string(kViewerScript) + "</script>\n";
    return out;
}

}  // namespace

std::string report_page_html(const ReportPageInput& in) {
    const json& s = in.summary;
    const json& files = s["files"];
    std::string overrides;
    for (const auto& o : s.value("overrides", json::array())) overrides += " --set " + o.get<std::string>();
    std::string out = page_begin(in.name, "<code>shatter run " + html_escape(s.value("shot", "") + overrides) + "</code>");
    if (!s["simulation"].value("complete", true))
        out += "<p class=\"note bad\">The simulation went unstable and stopped early: the trajectory and everything made "
               "from it end there (see the stability rows below and run.log).</p>\n";
    // What prescore and simulate warned of (the model's and the trajectory's own), where it is seen.
    std::string warned;
    for (const StageWarning& w : summary_warnings(s))
        warned += fmt::format("<li><span class=\"muted\">{}:</span> {}</li>\n", w.stage, html_escape(w.text));
    if (!warned.empty()) out += "<div class=\"note\" id=\"warnings\"><strong>Warnings</strong>\n<ul>\n" + warned + "</ul>\n</div>\n";

    out += media_section(files, in.name);
    out += viewer_section(in);

    out += "<h2>Summary</h2>\n<div class=\"grid\">\n<div>\n<h3>Fracture</h3>\n<table id=\"summary\">\n";
    out += summary_row(s, "pieces", "/model/pieces", "");
    out += summary_row(s, "constraints", "/model/constraints", "");
    out += summary_row(s, "tets", "/model/tets", "");
    out += summary_row(s, "collision parts", "/model/collision_parts", "");
    out += summary_row(s, "frames", "/simulation/frames", "");
    out += summary_row(s, "frame rate", "/simulation/fps", "fps");
    out += summary_row(s, "complete", "/simulation/complete", "");
    out += summary_row(s, "breaks", "/simulation/breaks", "", "constraints broken");
    out += summary_row(s, "first break", "/simulation/first_break_s", "s");
    out += summary_row(s, "fragments", "/simulation/fragments", "", "groups of pieces still joined at the end");
    out += summary_row(s, "peak piece speed", "/simulation/peak_piece_speed_m_per_s", "m/s");
    out += summary_row(s, "velocity clamps", "/instability/clamps", "", "steps the instability guard clamped");
    out += "</table>\n</div>\n<div>\n<h3>Energy books</h3>\n<table id=\"books\">\n";
    out += summary_row(s, "alpha", "/alpha", "", "share of the stored energy given back");
    out += summary_row(s, "stored at the breaks", "/simulation/stored_energy_J", "J");
    out += summary_row(s, "injected", "/simulation/injected_energy_J", "J", "kinetic energy the kicks added");
    out += summary_row(s, "kinetic, 0.1 s after the first break", "/simulation/kinetic_energy_after_first_break_J", "J");
    out += summary_row(s, "spread, 0.1 s after the first break", "/simulation/spread_energy_after_first_break_J", "J",
                       "relative to the common centre of mass");
    out += "</table>\n<h3>Time per stage</h3>\n<table id=\"times\"><thead><tr><th>stage</th><th class=\"num\">latest run"
           "</th><th class=\"num\">when it last ran</th></tr></thead><tbody></tbody></table>\n";
    out += "<script src=\"report.times.js\"></script>\n<script>" + std::string(kTimesScript) + "</script>\n";
    out += "</div>\n</div>\n";

    if (s["model"].contains("auto") || s["simulation"].contains("auto")) {
        out += "<h2>What was chosen for the mesh</h2>\n<p class=\"muted\">Each choice prescore and simulate made "
               "because the shot left it open or the mesh needed it, and why (the settings named there change it).</p>\n"
               "<table id=\"chosen\">\n";
        for (const char* stage : {"model", "simulation"})
            for (const json& c : s[stage].value("auto", json::array()))
                out += fmt::format("<tr><td class=\"muted\">{}</td><th>{}</th><td>{}</td></tr>\n",
                                   stage == std::string("model") ? "prescore" : "simulate",
                                   html_escape(c.value("what", std::string())), html_escape(c.value("why", std::string())));
        out += "</table>\n";
    }

    out += "<h2>Files</h2>\n<table id=\"files\">\n";
    for (const auto& [what, name] : files.items()) {
        const std::string n = name.get<std::string>();
        const std::string link = what == "frames" ? "frames/" : n;
        out += fmt::format("<tr><th>{}</th><td><a href=\"{}\">{}</a></td></tr>\n", html_escape(what), url_path(link),
                           html_escape(what == "frames" ? "frames/" : n));
    }
    for (const char* extra : {"summary.json", "run.log", "report.times.js"})
        out += fmt::format("<tr><th>{0}</th><td><a href=\"{0}\">{0}</a></td></tr>\n", extra);
    out += "</table>\n";

    out += "<h2>Settings</h2>\n<p class=\"muted\">The shot's settings after the overrides, as the stages read them.</p>\n"
           "<div class=\"grid\">\n";
    for (const auto& [section, values] : in.settings.items()) {
        out += "<div><h3>[" + html_escape(section) + "]</h3>\n<table>\n";
        if (values.is_object()) {
            for (const auto& [key, v] : values.items())
                out += "<tr><th>" + html_escape(key) + "</th><td><code>" + html_escape(setting_text(v)) + "</code></td></tr>\n";
        } else {
            out += "<tr><td><code>" + html_escape(setting_text(values)) + "</code></td></tr>\n";
        }
        out += "</table></div>\n";
    }
    out += "</div>\n";
    return out + page_end();
}

std::string report_times_js(const json& stages, const std::string& previous) {
    std::map<std::string, json> last_ran;
    const size_t begin = previous.find('['), end = previous.rfind(']');
    if (begin != std::string::npos && end != std::string::npos && end > begin) {
        try {
            for (const auto& s : json::parse(previous.substr(begin, end - begin + 1)))
                last_ran[s.at("stage").get<std::string>()] = s.at("last_ran_s");
        } catch (const std::exception&) {
            // an old or damaged file: no previous times
        }
    }
    json out = json::array();
    for (const auto& s : stages) {
        json row = s;
        const std::string stage = s.at("stage").get<std::string>();
        row["last_ran_s"] = s.at("outcome") == "ran" ? s.at("seconds")
                            : last_ran.count(stage) ? last_ran[stage]
                                                    : json(nullptr);
        out.push_back(row);
    }
    return "window.shatterStageTimes = " + out.dump() + ";\n";
}

}  // namespace shatter

namespace shatter {

json shot_settings(const Shot& shot) {
    json s;
    if (shot.generate) s["generate"] = to_json(*shot.generate);
    else s["mesh"] = to_json(shot.mesh);
    s["prescore"] = to_json(shot.prescore);
    s["scene"] = to_json(shot.scene);
    s["object"] = to_json(shot.object);
    s["material"] = to_json(shot.material);
    s["simulate"] = to_json(shot.simulate);
    s["render"] = to_json(shot.render);
    return s;
}

json report_stage_inputs(const std::string& dir, const std::string& name, const Shot& shot, const json& summary) {
    json inputs = {{"summary", summary}, {"settings", shot_settings(shot)}};
    const fs::path glb = fs::path(dir) / (name + ".glb");
    std::error_code ec;
    inputs["glb"] = fs::exists(glb, ec) ? json(file_hash(glb.string())) : json(nullptr);
    std::string why;
    if (const auto viewer = find_viewer(&why)) {
        json files = json::object();
        for (const ViewerFile& f : kViewerFiles) files[f.name] = file_hash((fs::path(*viewer) / f.package_path).string());
        inputs["viewer"] = files;
    } else {
        inputs["viewer"] = "not found in " + why;
    }
    return inputs;
}

std::vector<std::string> report_stage_outputs() {
    std::vector<std::string> out = {"report.html"};
    if (find_viewer())
        for (const ViewerFile& f : kViewerFiles) out.push_back(std::string("viewer/") + f.name);
    return out;
}

void write_report(const std::string& dir, const std::string& name, const Shot& shot, const json& summary) {
    if (summary.empty())
        throw Error(ExitCode::BadInput, fmt::format("{}: no summary.json to report (fix: run the stages before: shatter "
                                                    "run SHOT -o {})", dir, dir));
    ReportPageInput in;
    in.name = name;
    in.summary = summary;
    in.settings = shot_settings(shot);
    const fs::path glb = fs::path(dir) / (name + ".glb");
    std::error_code ec;
    if (fs::exists(glb, ec)) in.glb = read_file(glb.string(), "glTF export");
    const fs::path viewer_dir = fs::path(dir) / "viewer";
    if (const auto viewer = find_viewer(&in.viewer_missing)) {
        make_directories(viewer_dir.string());
        for (const ViewerFile& f : kViewerFiles)
            write_file_atomic((viewer_dir / f.name).string(),
                              read_file((fs::path(*viewer) / f.package_path).string(), "viewer script"));
        in.viewer = true;
    } else {
        fs::remove_all(viewer_dir, ec);
    }
    write_file_atomic((fs::path(dir) / "report.html").string(), report_page_html(in));
}

void write_report_times(const std::string& dir, const std::vector<StageReport>& stages) {
    json rows = json::array();
    for (const StageReport& s : stages)
        rows.push_back({{"stage", to_string(s.stage)}, {"outcome", to_string(s.outcome)}, {"seconds", std::round(s.seconds * 100) / 100}});
    const std::string path = (fs::path(dir) / "report.times.js").string();
    std::string previous;
    std::error_code ec;
    if (fs::is_regular_file(path, ec)) previous = read_file(path, "stage times");
    write_file_atomic(path, report_times_js(rows, previous));
}

}  // namespace shatter
