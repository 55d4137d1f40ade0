#include "html_report.h"

#include <cmath>
#include <map>

#include "dlslam/io/file_util.h"

namespace dlslam::app {

namespace {

constexpr std::size_t kMaxMapPoints = 30000;

long Mm(double metres) { return std::lround(metres * 1000.0); }

// The page: plain canvas drawing, no library. DATA is inserted for
// @DATA@; the page reports what it drew in #status (the browser test reads it).
constexpr const char* kPage = R"html(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>DLSLAM run</title>
<style>
body{font:14px system-ui,sans-serif;margin:16px;color:#222;background:#fafafa}
h1{font-size:20px;margin:0 0 8px} h2{font-size:16px;margin:18px 0 6px}
.grid{display:flex;flex-wrap:wrap;gap:16px} .card{background:#fff;border:1px solid #ddd;border-radius:6px;padding:10px}
canvas{background:#fff;border:1px solid #eee;display:block} table{border-collapse:collapse}
td,th{padding:2px 10px;text-align:right;border-bottom:1px solid #eee} th:first-child,td:first-child{text-align:left}
.key span{display:inline-block;width:10px;height:10px;margin:0 4px 0 12px} pre{max-height:400px;overflow:auto;background:#fff}
</style></head><body>
<h1 id="title"></h1><div id="summary"></div><p id="status">drawing...</p>
<div class="grid">
<div class="card" id="frame-card" style="display:none"><h2>Current frame: kept (green) and removed (red) keypoints, removed regions</h2>
<img id="frame" width="640" height="480" alt="current frame"></div>
<div class="card"><h2>Trajectory (top view)</h2><canvas id="trajectory" width="520" height="420"></canvas>
<div class="key"><span style="background:#999"></span>ground truth<span style="background:#1565c0"></span>tracked
<span style="background:#2e7d32"></span>relocalized<span style="background:#ef6c00"></span>coasted
<span style="background:#8e24aa"></span>new map</div></div>
<div class="card"><h2>Absolute trajectory error</h2><canvas id="error" width="520" height="420"></canvas></div>
<div class="card"><h2>Map: points and keyframes (drag to orbit, wheel to zoom)</h2><canvas id="map" width="700" height="520"></canvas></div>
<div class="card"><h2>Time per stage</h2><table id="timings"></table></div>
</div>
<h2>Options</h2><details><summary>effective options of this run</summary><pre id="options"></pre></details>
<script>
const colour = {t: '#1565c0', r: '#2e7d32', c: '#ef6c00', n: '#8e24aa'};
function extent(points, a) {
  let lo = Infinity, hi = -Infinity;
  for (const p of points) { lo = Math.min(lo, p[a]); hi = Math.max(hi, p[a]); }
  return [lo, hi];
}
function axes(points) {  // the two axes with the largest extent
  const ext = [0, 1, 2].map(a => { const [lo, hi] = extent(points, a); return hi - lo; });
  return [0, 1, 2].sort((a, b) => ext[b] - ext[a]).slice(0, 2);
}
function fit(canvas, points, [a, b]) {
  const [x0, x1] = extent(points, a), [y0, y1] = extent(points, b);
  const s = 0.9 * Math.min(canvas.width / Math.max(x1 - x0, 1), canvas.height / Math.max(y1 - y0, 1));
  return p => [canvas.width / 2 + (p[a] - (x0 + x1) / 2) * s, canvas.height / 2 - (p[b] - (y0 + y1) / 2) * s];
}
const EMBEDDED = @DATA@;  // null in the live view, which fetches data.json
const $ = id => document.getElementById(id);
let yaw = 0.6, pitch = 0.5, zoom = 1;
function render(DATA) {
const drawn = [];
for (const id of ['trajectory', 'error', 'map']) $(id).getContext('2d').clearRect(0, 0, $(id).width, $(id).height);
$('title').textContent = 'DLSLAM: ' + DATA.title;
{
  const s = DATA.summary, parts = [`mode ${s.mode}`, `${s.frames_posed} / ${s.frames} frames posed`];
  if (s.state) parts.push(`tracking ${s.state}`);
  for (const [k, v] of Object.entries(s.pose_sources)) parts.push(`${k} ${v}`);
  if (s.ate_rmse !== null) parts.push(`ATE RMSE ${(s.ate_rmse * 1000).toFixed(1)} mm`);
  parts.push(`${s.keyframes} keyframes`, `${s.map_points} map points`);
  $('summary').textContent = parts.join(' \u00b7 ');
}
if (DATA.trajectory.length > 1) {
  const c = $('trajectory'), g = c.getContext('2d');
  const all = DATA.trajectory.map(p => p.est).concat(DATA.trajectory.filter(p => p.gt).map(p => p.gt));
  const to = fit(c, all, axes(all));
  const line = (key, col) => {
    g.strokeStyle = col; g.lineWidth = 1.5; g.beginPath();
    DATA.trajectory.filter(p => p[key]).forEach((p, i) => { const [x, y] = to(p[key]); i ? g.lineTo(x, y) : g.moveTo(x, y); });
    g.stroke();
  };
  line('gt', '#999');
  for (const p of DATA.trajectory) { const [x, y] = to(p.est); g.fillStyle = colour[p.source] || '#000'; g.fillRect(x - 1.5, y - 1.5, 3, 3); }
  drawn.push('trajectory');
}
if (DATA.trajectory.some(p => p.error !== undefined)) {
  const c = $('error'), g = c.getContext('2d'), pts = DATA.trajectory.filter(p => p.error !== undefined);
  const t0 = pts[0].t, t1 = pts[pts.length - 1].t, e1 = pts.reduce((m, p) => Math.max(m, p.error), 0) || 1;
  const X = t => 50 + (t - t0) / Math.max(t1 - t0, 1e-9) * (c.width - 70), Y = e => c.height - 30 - e / e1 * (c.height - 50);
  g.strokeStyle = '#ccc'; g.strokeRect(50, 20, c.width - 70, c.height - 50);
  g.fillStyle = '#444'; g.fillText(`${(e1 * 1000).toFixed(0)} mm`, 4, 24); g.fillText('0', 36, c.height - 30);
  g.fillText(`${(t1 - t0).toFixed(1)} s`, c.width - 50, c.height - 12);
  g.strokeStyle = '#c62828'; g.beginPath();
  pts.forEach((p, i) => i ? g.lineTo(X(p.t), Y(p.error)) : g.moveTo(X(p.t), Y(p.error))); g.stroke();
  drawn.push('error');
} else { $('error').getContext('2d').fillText('no ground truth', 20, 30); }
{
  const c = $('map'), g = c.getContext('2d'), pts = DATA.map_points, kfs = DATA.keyframes;
  const all = pts.concat(kfs);
  if (all.length) {
    const mean = [0, 1, 2].map(a => all.reduce((s, p) => s + p[a], 0) / all.length);
    const radius = Math.sqrt(all.reduce((s, p) => s + (p[0] - mean[0]) ** 2 + (p[1] - mean[1]) ** 2 + (p[2] - mean[2]) ** 2, 0) / all.length) || 1;
    const draw = () => {
      g.clearRect(0, 0, c.width, c.height);
      const cy = Math.cos(yaw), sy = Math.sin(yaw), cp = Math.cos(pitch), sp = Math.sin(pitch);
      const f = 0.9 * c.height * zoom, dist = 3 * radius;
      const project = p => {
        const x = p[0] - mean[0], y = p[1] - mean[1], z = p[2] - mean[2];
        const x1 = cy * x + sy * z, z1 = -sy * x + cy * z, y2 = cp * y - sp * z1, z2 = sp * y + cp * z1 + dist;
        return z2 > 1 ? [c.width / 2 + f * x1 / z2, c.height / 2 + f * y2 / z2] : null;
      };
      g.fillStyle = 'rgba(30,30,30,0.55)';
      for (const p of pts) { const q = project(p); if (q) g.fillRect(q[0], q[1], 1.6, 1.6); }
      g.strokeStyle = '#1565c0'; g.beginPath(); let first = true;
      for (const p of kfs) { const q = project(p); if (!q) continue; first ? g.moveTo(q[0], q[1]) : g.lineTo(q[0], q[1]); first = false; }
      g.stroke(); g.fillStyle = '#1565c0';
      for (const p of kfs) { const q = project(p); if (q) g.fillRect(q[0] - 2.5, q[1] - 2.5, 5, 5); }
    };
    let drag = null;
    c.onmousedown = e => drag = [e.clientX, e.clientY, yaw, pitch];
    window.onmouseup = () => drag = null;
    c.onmousemove = e => { if (!drag) return; yaw = drag[2] + (e.clientX - drag[0]) * 0.01; pitch = drag[3] + (e.clientY - drag[1]) * 0.01; draw(); };
    c.onwheel = e => { e.preventDefault(); zoom *= e.deltaY < 0 ? 1.1 : 1 / 1.1; draw(); };
    draw(); drawn.push('map');
  }
}
{
  const rows = Object.entries(DATA.timings).sort((a, b) => b[1].median - a[1].median);
  $('timings').innerHTML = '<tr><th>stage</th><th>median ms</th><th>p95 ms</th><th>count</th></tr>' +
    rows.map(([k, v]) => `<tr><td>${k}</td><td>${v.median.toFixed(2)}</td><td>${v.p95.toFixed(2)}</td><td>${v.count}</td></tr>`).join('');
  drawn.push('timings');
}
$('options').textContent = JSON.stringify(DATA.options, null, 2);
// Which canvases hold any drawn pixel (the browser test reads this line).
const nonblank = ['trajectory', 'error', 'map'].filter(id => {
  const c = $(id), d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
  for (let i = 3; i < d.length; i += 4) if (d[i]) return true;
  return false;
});
$('status').textContent = `frames ${DATA.summary.frames}, posed ${DATA.summary.frames_posed}; drawn: ${drawn.join(', ')}; nonblank: ${nonblank.join(', ')}`;
document.body.dataset.drawn = drawn.join(',');
}
if (EMBEDDED) {
  render(EMBEDDED);
} else {
  $('frame-card').style.display = '';
  const poll = async () => {
    try {
      const response = await fetch('data.json', {cache: 'no-store'});
      render(await response.json());
      $('frame').src = 'frame.jpg?' + Date.now();
    } catch (e) {
      $('status').textContent += ' (the run has ended: the server is gone)';
      return;
    }
    setTimeout(poll, 500);
  };
  poll();
}
</script></body></html>
)html";

}  // namespace

nlohmann::ordered_json PositionMm(const Eigen::Vector3d& p) { return {Mm(p.x()), Mm(p.y()), Mm(p.z())}; }

nlohmann::ordered_json MapPointsMm(const std::vector<Eigen::Vector3d>& points,
                                   const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& place) {
  const std::size_t step = std::max<std::size_t>(1, (points.size() + kMaxMapPoints - 1) / kMaxMapPoints);
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < points.size(); i += step) out.push_back(PositionMm(place(points[i])));
  return out;
}

nlohmann::ordered_json HtmlReportData(const HtmlReportInput& input) {
  const RunStats& stats = *input.stats;
  nlohmann::ordered_json d;
  d["title"] = input.title;
  nlohmann::ordered_json& s = d["summary"];
  s["mode"] = ToString(stats.dynamic.mode);
  s["frames"] = stats.frames;
  s["frames_posed"] = stats.frames_posed();
  s["pose_sources"] = PoseSourcesReport(stats);
  const std::optional<RunEvaluation>& evaluation = *input.evaluation;
  s["ate_rmse"] = evaluation ? nlohmann::ordered_json(evaluation->ate.error.rmse) : nullptr;
  s["keyframes"] = stats.keyframes;
  s["map_points"] = stats.map_points;
  // Everything in the ground truth's frame when there is one.
  const auto place = [&](const Eigen::Vector3d& p) { return evaluation ? evaluation->ate.gt_from_est.Apply(p) : p; };
  std::map<double, char> source_of;
  for (const FramePoseSource& f : input.slam->FrameSources()) {
    source_of[f.timestamp] = PoseSourceLetter(f.source);
  }
  std::map<double, const eval::AtePair*> pair_of;
  if (evaluation) {
    for (const eval::AtePair& p : evaluation->ate.per_pair) pair_of[p.est_timestamp] = &p;
  }
  nlohmann::ordered_json trajectory = nlohmann::ordered_json::array();
  for (const StampedPose& pose : input.slam->CameraTrajectory()) {
    nlohmann::ordered_json e;
    e["t"] = pose.timestamp;
    e["est"] = PositionMm(place(pose.translation));
    if (const auto it = pair_of.find(pose.timestamp); it != pair_of.end()) {
      e["gt"] = PositionMm(it->second->gt_position);
      e["error"] = it->second->error;
    }
    const auto src = source_of.find(pose.timestamp);
    e["source"] = std::string(1, src == source_of.end() ? 't' : src->second);
    trajectory.push_back(std::move(e));
  }
  d["trajectory"] = std::move(trajectory);
  nlohmann::ordered_json keyframes = nlohmann::ordered_json::array();
  for (const StampedPose& k : input.slam->KeyFrameTrajectory()) keyframes.push_back(PositionMm(place(k.translation)));
  d["keyframes"] = std::move(keyframes);
  d["map_points"] = MapPointsMm(input.slam->MapPointPositions(), place);
  d["timings"] = TimingsReport(stats.timing_ms);
  d["options"] = input.options;
  return d;
}

std::string HtmlReportPage(const nlohmann::ordered_json& data) {
  std::string json = data.dump();
  // Inside <script>, "</" could end it: JSON allows "<\/".
  for (std::size_t at = json.find("</"); at != std::string::npos; at = json.find("</", at + 3)) json.replace(at, 2, "<\\/");
  std::string page = kPage;
  const std::size_t at = page.find("@DATA@");
  page.replace(at, 6, json);
  return page;
}

void WriteHtmlReport(const std::filesystem::path& path, const HtmlReportInput& input) {
  const std::string page = HtmlReportPage(HtmlReportData(input));
  io::WriteFileAtomically(path, [&](std::ostream& out) { out << page; });
}

}  // namespace dlslam::app
