// coopdrive HMI: draws the live frames of /ws (LiveFrame, see the gateway's view_models.py).
// window.hmi holds what was drawn last, so tests and operators' tools can read it.
"use strict";

// Lateral distances are drawn stretched: at one scale a lane would be a thin strip across the canvas.
const VIEW = { behindM: 20, aheadM: 90, lanesEachSide: 1, lateralStretch: 2.5 };
const GAUGES = { speedKmh: 150, gapM: 100, timeGapS: 4 };
const SHORT_TIME_GAP_S = 0.8;
const ALERT_REPEAT_MS = 10000;
const RECONNECT_MIN_MS = 500;
const RECONNECT_MAX_MS = 5000;
const CLASS_COLOURS = { car: "216,221,227", truck: "190,160,120", emergency_vehicle: "240,90,90",
                        obstacle: "170,120,200", unspecified: "200,200,200" };

const hmi = window.hmi = {
  connected: false, frames: 0, frame: null,
  drawn: { objects: [], lanes: [], links: [] },
  gauges: { speedKmh: null, gapM: null, timeGapS: null },
  alerts: [], lastCommand: null,
};

const $ = (id) => document.getElementById(id);
const fmt = (v, digits) => (v === null || v === undefined || Number.isNaN(v)) ? "–" : v.toFixed(digits);

// ----- alerts: on screen and spoken ------------------------------------------------------------
const spokenAt = new Map();
function alertOperator(text) {
  const now = Date.now();
  $("alert").textContent = text;
  hmi.alerts.push({ text, at: now });
  if (hmi.alerts.length > 50) hmi.alerts.shift();
  if ((spokenAt.get(text) || 0) + ALERT_REPEAT_MS > now) return;
  spokenAt.set(text, now);
  try {
    if ("speechSynthesis" in window && typeof SpeechSynthesisUtterance === "function") {
      window.speechSynthesis.speak(new SpeechSynthesisUtterance(text));
    }
  } catch (error) { /* no voice on this device: the alert stays on screen */ }
}

function watchForAlerts(previous, frame) {
  if (!previous) return;
  if (previous.mode !== frame.mode && frame.mode) {
    alertOperator(`Mode ${frame.mode.replace("_", " ")}` + (frame.mode_change_reason ? `: ${frame.mode_change_reason}` : ""));
  }
  const hadLead = previous.gap_m !== null, hasLead = frame.gap_m !== null;
  if (hadLead !== hasLead) alertOperator(hasLead ? "Vehicle ahead" : "No vehicle ahead");
  if (frame.time_gap_s !== null && frame.time_gap_s < SHORT_TIME_GAP_S &&
      !(previous.time_gap_s !== null && previous.time_gap_s < SHORT_TIME_GAP_S)) alertOperator("Short time gap");
  // Only a partner we heard can be lost: a station listed only because its packets are refused never was one.
  const activeBefore = new Set(previous.stations.filter((s) => s.state === "active").map((s) => s.station_id));
  for (const s of frame.stations) {
    if (s.state === "lost" && activeBefore.has(s.station_id)) alertOperator(`V2V partner ${s.station_id} lost`);
  }
  if (previous.planner_state !== frame.planner_state && frame.planner_state) {
    $("alert").textContent = `Planner: ${frame.planner_state}`;
  }
}

// ----- bird's-eye view ---------------------------------------------------------------------------
function drawBirdseye(frame) {
  const canvas = $("birdseye"), ctx = canvas.getContext("2d");
  const w = canvas.width, h = canvas.height;
  const scale = w / (VIEW.behindM + VIEW.aheadM);  // px per metre along the road
  const lat = scale * VIEW.lateralStretch;  // px per metre across it
  // Ego frame: x ahead (to the right on screen), y left (up on screen).
  const toX = (xm) => (xm + VIEW.behindM) * scale;
  const toY = (ym) => h / 2 - ym * lat;
  ctx.clearRect(0, 0, w, h);
  const laneW = frame.lane_width_m, egoCentreY = -frame.lateral_offset_m;
  const lanes = [];
  // Without a map the ego lane is unknown: drawn as the middle one.
  const egoLane = frame.ego_lane_index === null ? VIEW.lanesEachSide : frame.ego_lane_index;
  const lowest = Math.max(0, egoLane - VIEW.lanesEachSide), highest = egoLane + VIEW.lanesEachSide;
  ctx.fillStyle = "#3a4048";
  const roadRight = egoCentreY + (lowest - egoLane - 0.5) * laneW;
  const roadLeft = egoCentreY + (highest - egoLane + 0.5) * laneW;
  ctx.fillRect(0, toY(roadLeft), w, toY(roadRight) - toY(roadLeft));
  for (let k = lowest; k <= highest + 1; k++) {
    const y = egoCentreY + (k - egoLane - 0.5) * laneW, outer = k === lowest || k === highest + 1;
    ctx.strokeStyle = "#e8edf2"; ctx.lineWidth = outer ? 3 : 2;
    ctx.setLineDash(outer ? [] : [3 * scale, 9 * scale]);
    ctx.beginPath(); ctx.moveTo(0, toY(y)); ctx.lineTo(w, toY(y)); ctx.stroke();
    lanes.push({ boundary_y_m: y, outer });
  }
  ctx.setLineDash([]);
  // Distance marks every 20 m.
  ctx.fillStyle = "#9aa7b3"; ctx.font = "12px system-ui";
  for (let m = -20; m <= VIEW.aheadM; m += 20) ctx.fillText(`${m} m`, toX(m) + 2, h - 6);

  const stations = new Map(frame.stations.map((s) => [s.station_id, s]));
  const drawn = [], links = [];
  for (const o of frame.objects) {
    ctx.save();
    ctx.translate(toX(o.x_m), toY(o.y_m));
    ctx.scale(1, VIEW.lateralStretch);
    ctx.rotate(-o.heading_rad);
    const alpha = 0.2 + 0.8 * Math.min(1, Math.max(0, o.confidence));
    ctx.fillStyle = `rgba(${CLASS_COLOURS[o.object_class] || CLASS_COLOURS.unspecified},${alpha.toFixed(2)})`;
    ctx.fillRect(0, -o.width_m / 2 * scale, o.length_m * scale, o.width_m * scale);
    if (o.forward_mio) { ctx.strokeStyle = "#ffcf5c"; ctx.lineWidth = 2;
      ctx.strokeRect(0, -o.width_m / 2 * scale, o.length_m * scale, o.width_m * scale); }
    ctx.restore();
    ctx.fillStyle = "#e8edf2";
    ctx.fillText(`#${o.id} ${Math.round(o.confidence * 100)}%`, toX(o.x_m), toY(o.y_m) - o.width_m / 2 * lat - 4);
    if (o.forward_mio && frame.gap_m !== null) {
      const y = toY(o.y_m) + o.width_m / 2 * lat + 14;
      ctx.strokeStyle = "#ffcf5c"; ctx.lineWidth = 1;
      ctx.beginPath(); ctx.moveTo(toX(o.x_m - frame.gap_m), y); ctx.lineTo(toX(o.x_m), y); ctx.stroke();
      ctx.fillStyle = "#ffcf5c";
      ctx.fillText(`${frame.gap_m.toFixed(1)} m`, toX(o.x_m - frame.gap_m / 2) - 16, y + 14);
    }
    const station = o.station_id !== null ? stations.get(o.station_id) : undefined;
    if (station) {
      ctx.strokeStyle = station.state === "active" ? "#4cd07d" : "#e5534b";
      ctx.setLineDash(station.state === "active" ? [] : [6, 6]); ctx.lineWidth = 2;
      ctx.beginPath(); ctx.moveTo(toX(0), toY(0)); ctx.lineTo(toX(o.x_m), toY(o.y_m)); ctx.stroke();
      ctx.setLineDash([]);
      links.push({ station_id: station.station_id, object_id: o.id, state: station.state, trust: station.trust });
    }
    drawn.push({ id: o.id, x_m: o.x_m, y_m: o.y_m, confidence: o.confidence, object_class: o.object_class,
                 forward_mio: o.forward_mio, station_id: o.station_id, alpha });
  }
  // The ego: reference at its rear axle, body from about 1 m behind it.
  ctx.fillStyle = "#3fa9f5";
  ctx.fillRect(toX(-1.0), toY(0.9), 4.5 * scale, 1.8 * lat);
  hmi.drawn = { objects: drawn, lanes, links, scale };
  canvas.dataset.objects = String(drawn.length);
  canvas.dataset.forwardMio = String((drawn.find((o) => o.forward_mio) || {}).id ?? "");
}

// ----- gauges ------------------------------------------------------------------------------------
function drawGauge(id, value, max, redBelow) {
  const canvas = $(id), ctx = canvas.getContext("2d"), w = canvas.width, h = canvas.height;
  const cx = w / 2, cy = h - 10, r = Math.min(w / 2, h) - 14;
  ctx.clearRect(0, 0, w, h);
  ctx.lineWidth = 14; ctx.lineCap = "butt";
  ctx.strokeStyle = "#2b3036"; ctx.beginPath(); ctx.arc(cx, cy, r, Math.PI, 2 * Math.PI); ctx.stroke();
  if (redBelow) { ctx.strokeStyle = "#6b2a2a"; ctx.beginPath();
    ctx.arc(cx, cy, r, Math.PI, Math.PI * (1 + redBelow / max)); ctx.stroke(); }
  if (value === null || Number.isNaN(value)) return;
  const f = Math.min(1, Math.max(0, value / max));
  ctx.strokeStyle = redBelow && value < redBelow ? "#e5534b" : "#3fa9f5";
  ctx.beginPath(); ctx.arc(cx, cy, r, Math.PI, Math.PI * (1 + f)); ctx.stroke();
}

function setValue(id, value, digits) {
  const el = $(id);
  el.textContent = fmt(value, digits);
  el.dataset.value = value === null || value === undefined ? "" : String(value);
}

function drawGauges(frame) {
  const kmh = frame.speed_mps === null ? null : frame.speed_mps * 3.6;
  hmi.gauges = { speedKmh: kmh, gapM: frame.gap_m, timeGapS: frame.time_gap_s };
  setValue("speed", kmh, 0); setValue("gap", frame.gap_m, 1); setValue("time-gap", frame.time_gap_s, 2);
  drawGauge("gauge-speed", kmh, GAUGES.speedKmh);
  drawGauge("gauge-gap", frame.gap_m, GAUGES.gapM);
  drawGauge("gauge-timegap", frame.time_gap_s, GAUGES.timeGapS, 1.0);
}

// ----- panels ------------------------------------------------------------------------------------
function listItems(el, items) {
  el.replaceChildren(...items.map(([text, cls]) => {
    const li = document.createElement("li"); li.textContent = text; if (cls) li.className = cls; return li;
  }));
}

function drawPanels(frame) {
  $("clock").textContent = `t = ${fmt(frame.clock_s, 1)} s`;
  $("scenario").textContent = frame.scenario || "–";
  const state = $("planner-state");
  state.textContent = frame.planner_state || "–"; state.dataset.state = frame.planner_state || "";
  $("time-in-state").textContent = `${fmt(frame.time_in_state_s, 1)} s`;
  const mode = $("mode");
  mode.textContent = frame.mode ? frame.mode.replace("_", " ") : "–"; mode.dataset.mode = frame.mode || "";
  $("mode-reason").textContent = frame.mode_change_reason ? `last change: ${frame.mode_change_reason}` : "";
  listItems($("availability"), frame.availability.map((a) => a.available
    ? [`${a.mode}: available`, "yes"] : [`${a.mode}: unavailable — ${a.unmet_condition || "unknown"}`, "no"]));
  listItems($("stations"), frame.stations.length ? frame.stations.map((s) =>
    [`#${s.station_id} ${s.state}, trust ${fmt(s.trust, 2)}, reception ${fmt(s.reception_ratio * 100, 0)}%, `
     + securityText(s), s.state === "active" ? "yes" : "no"]) : [["none heard", "muted"]]);
}

// What the station's last packet showed: unsigned, or signed and how far it checked out (and why not).
function securityText(s) {
  if (!s.signed) return s.last_security_reason ? `unsigned (${s.last_security_reason})` : "unsigned";
  const checks = [s.verified ? "verified" : "not verified", s.trusted ? "trusted" : "not trusted"].join(", ");
  return `signed, ${checks}` + (s.last_security_reason ? ` (${s.last_security_reason})` : "");
}

function render(frame) {
  watchForAlerts(hmi.frame, frame);
  hmi.frame = frame; hmi.frames += 1;
  drawBirdseye(frame); drawGauges(frame); drawPanels(frame);
}

// ----- live connection, reconnecting by itself ---------------------------------------------------
let retryMs = RECONNECT_MIN_MS;
function setConnected(connected) {
  if (hmi.connected && !connected) alertOperator("Connection to the vehicle lost");
  hmi.connected = connected;
  const el = $("connection");
  el.textContent = connected ? "live" : "reconnecting…";
  el.className = `pill ${connected ? "ok" : "bad"}`; el.dataset.state = connected ? "live" : "reconnecting";
}

function connect() {
  const token = $("token").value.trim();
  const url = `${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/ws` +
              (token ? `?token=${encodeURIComponent(token)}` : "");
  let socket;
  try { socket = new WebSocket(url); } catch (error) { setTimeout(connect, retryMs); return; }
  socket.onopen = () => { retryMs = RECONNECT_MIN_MS; setConnected(true); };
  socket.onmessage = (event) => {
    try { render(JSON.parse(event.data)); } catch (error) { console.error("bad frame", error); }
  };
  socket.onclose = () => {
    setConnected(false);
    setTimeout(connect, retryMs);
    retryMs = Math.min(RECONNECT_MAX_MS, retryMs * 2);
  };
}

// ----- commands ----------------------------------------------------------------------------------
async function requestMode() {
  const result = $("command-result"), token = $("token").value.trim();
  const body = { mode: $("mode-select").value, reason: $("reason").value.trim() };
  const headers = { "Content-Type": "application/json" };
  if (token) headers.Authorization = `Bearer ${token}`;
  result.textContent = "sending…"; result.dataset.outcome = "";
  let outcome, text;
  try {
    const response = await fetch("/mode", { method: "POST", headers, body: JSON.stringify(body) });
    const answer = await response.json().catch(() => ({}));
    if (response.ok) {
      outcome = "sent"; text = `Sent: ${answer.detail || body.mode}`;
    } else {
      const detail = typeof answer.detail === "string" ? answer.detail
        : Array.isArray(answer.detail) ? answer.detail.map((d) => `${d.loc?.slice(-1)[0]}: ${d.msg}`).join("; ")
        : response.statusText;
      outcome = "refused"; text = `Refused (${response.status}): ${detail}`;
    }
    hmi.lastCommand = { status: response.status, outcome, text };
  } catch (error) {
    outcome = "refused"; text = `Not sent: ${error}`;
    hmi.lastCommand = { status: 0, outcome, text };
  }
  result.textContent = text; result.dataset.outcome = outcome;
  if (outcome === "refused") alertOperator("Mode change refused");
}

$("mode-button").addEventListener("click", requestMode);
setConnected(false);
connect();
