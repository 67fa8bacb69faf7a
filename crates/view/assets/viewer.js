'use strict';
// platoonsim replay viewer. Plain JavaScript on Canvas 2D; everything it shows is in this
// page (a JSON block and a gzip+base64 block written by `platoonsim view`). Positions are in
// the run's output coordinate (metres), lanes numbered from the right (1 = rightmost).

(async function main() {
  const meta = JSON.parse(document.getElementById('meta').textContent);
  // Text from the run's files as HTML text: the browser's own escaping.
  const esc = (text) => { const d = document.createElement('div'); d.textContent = String(text); return d.innerHTML; };
  const road = meta.road;
  const D = await unpack(meta, document.getElementById('data').textContent.trim());
  const L = road.vehicle_length_m;
  const frames = meta.frames;
  const F = frames.length;

  // ---- colours -------------------------------------------------------------------------
  const KIND = { cav: [0, 114, 178], human: [150, 150, 150] };
  const OTHER_KIND = [120, 80, 160];
  const NO_PLATOON_CAV = [150, 190, 215];
  const HUMAN_FADED = [246, 246, 246];
  // Distinct platoon colours (no grey or light blue, which mean "not in a platoon").
  const PLATOON = [[213, 94, 0], [0, 158, 115], [204, 121, 167], [230, 159, 0], [0, 90, 200],
    [160, 40, 40], [110, 160, 20], [120, 60, 170], [0, 150, 170], [200, 60, 120]];
  const MODE = [[0, 114, 178], [150, 150, 150], [213, 94, 0], [230, 159, 0], [0, 158, 115],
    [204, 121, 167], [86, 180, 233], [120, 60, 30], [90, 90, 90], [200, 30, 35]];
  // The project's speed scale (0-120 km/h, red - yellow - green, 5 km/h steps).
  const SPEED_BIN_KMH = 5, SPEED_BINS = 24;
  function speedRgb(tt) {
    const stops = [[0, [200, 30, 35]], [0.5, [250, 215, 70]], [1, [30, 145, 70]]];
    const t = Math.min(1, Math.max(0, tt));
    const [a, b] = t <= 0.5 ? [stops[0], stops[1]] : [stops[1], stops[2]];
    const f = (t - a[0]) / (b[0] - a[0]);
    return [0, 1, 2].map((k) => Math.round(a[1][k] + (b[1][k] - a[1][k]) * f));
  }
  const SPEED = [];
  for (let b = 0; b < SPEED_BINS; b++) SPEED.push(speedRgb((b + 0.5) / SPEED_BINS));
  const cssCache = new Map();
  const css = (c) => {
    let s = cssCache.get(c);
    if (s === undefined) { s = `rgb(${c[0]},${c[1]},${c[2]})`; cssCache.set(c, s); }
    return s;
  };
  const speedBin = (kmh) => Math.max(0, Math.min(SPEED_BINS - 1, Math.floor(kmh / SPEED_BIN_KMH)));

  // ---- state ---------------------------------------------------------------------------
  const el = (id) => document.getElementById(id);
  const canvas = el('road'), ctx = canvas.getContext('2d');
  const mini = el('minimap'), mctx = mini.getContext('2d');
  const contour = el('contour'), cctx = contour.getContext('2d');
  const S = {
    t: frames[0], playing: false, speed: 8, colour: 'kind', selected: -1, follow: false,
    x0: road.start_m, ppm: 1, lastWall: 0, drawn: 0, rafFrames: 0,
  };
  const colourModes = ['kind', 'speed', 'platoon', 'mode'];
  if (meta.regimes.length) {
    const o = document.createElement('option');
    o.value = 'regime'; o.textContent = 'CACC regime';
    el('colour').appendChild(o);
    colourModes.push('regime');
  }
  let W = 0, H = 0, laneH = 16, roadTop = 44;

  function resize() {
    // Lanes of 10 to 24 px; room above for the scale and below for the ramps.
    laneH = Math.max(10, Math.min(24, Math.floor(200 / road.lanes)));
    canvas.style.height = `${roadTop + road.lanes * laneH + 56}px`;
    const dpr = window.devicePixelRatio || 1;
    for (const c of [canvas, mini]) {
      const r = c.getBoundingClientRect();
      c.width = Math.round(r.width * dpr);
      c.height = Math.round(r.height * dpr);
      c.getContext('2d').setTransform(dpr, 0, 0, dpr, 0, 0);
    }
    W = canvas.getBoundingClientRect().width;
    H = canvas.getBoundingClientRect().height;
  }
  const laneY = (lane) => roadTop + (road.lanes - lane) * laneH + laneH / 2;
  const carH = () => Math.max(3, Math.round(laneH * 0.6));
  const sx = (x) => (x - S.x0) * S.ppm;
  function fitAll() {
    const span = road.end_m - road.start_m;
    S.ppm = (W - 20) / span;
    S.x0 = road.start_m - 10 / S.ppm;
  }
  function clampView() {
    const span = road.end_m - road.start_m;
    S.ppm = Math.max(Math.min((W - 20) / span, 0.02), Math.min(S.ppm, 40));
    const vis = W / S.ppm;
    S.x0 = Math.max(road.start_m - vis * 0.5, Math.min(S.x0, road.end_m - vis * 0.5));
  }

  // ---- frames and rows -----------------------------------------------------------------
  function frameAt(t) {
    let lo = 0, hi = F - 1;
    if (t <= frames[0]) return 0;
    if (t >= frames[F - 1]) return F - 1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (frames[mid] <= t + 1e-9) lo = mid; else hi = mid - 1;
    }
    return lo;
  }
  // The row of track k at frame f, or -1.
  function rowOf(k, f) {
    const d = f - D.tFirst[k];
    return d >= 0 && d < D.tLen[k] ? D.rowStart[k] + d : -1;
  }
  function trackOfId(id, f) {
    const ks = D.tracksById.get(id);
    if (!ks) return -1;
    for (const k of ks) if (rowOf(k, f) >= 0) return k;
    return -1;
  }
  const kindName = (k) => meta.kinds[D.tKind[k]] || '?';

  // Platoon strings of frame f: per row, the string's leader track (or -1) and whether it
  // leads. From platoon_pos when the run wrote it, else inferred (CAVs within 2 s).
  const platoonCache = { f: -1, group: null, leader: null, size: null };
  function platoons(f) {
    if (platoonCache.f === f) return platoonCache;
    const a = D.frameStart[f], b = D.frameStart[f + 1];
    const byLane = new Map();
    for (let i = a; i < b; i++) {
      const k = D.frameTracks[i], r = rowOf(k, f);
      const l = D.lane[r];
      if (!byLane.has(l)) byLane.set(l, []);
      byLane.get(l).push(k);
    }
    const group = new Map(), leader = new Set(), size = new Map();
    for (const unsorted of byLane.values()) {
      // Front first: sort (x, track) pairs packed in one Float64Array.
      const xs = new Float64Array(unsorted.length);
      const idx = unsorted.map((k, j) => { xs[j] = -D.x[rowOf(k, f)]; return j; });
      idx.sort((p, q) => xs[p] - xs[q]);
      const list = idx.map((j) => unsorted[j]);
      for (let j = 0; j < list.length; j++) {
        const k = list[j], r = rowOf(k, f);
        let g = k;
        if (j > 0) {
          const ahead = list[j - 1], ra = rowOf(ahead, f);
          let joins;
          if (meta.platoon_column) {
            joins = D.pos[r] > 1;
          } else {
            const v = D.v[r] * meta.speed_unit_kmh / 3.6;
            const gap = D.x[ra] - L - D.x[r];
            joins = kindName(k) === 'cav' && kindName(ahead) === 'cav' &&
              (v > 0.5 ? gap / v <= 2.0 : gap <= 5);
          }
          if (joins) g = group.get(ahead);
        }
        group.set(k, g);
        size.set(g, (size.get(g) || 0) + 1);
      }
    }
    for (const [k, g] of group) if (g === k && size.get(g) > 1) leader.add(k);
    Object.assign(platoonCache, { f, group, leader, size });
    return platoonCache;
  }

  function colourOf(k, r, f) {
    const kind = kindName(k);
    switch (S.colour) {
      case 'speed': return SPEED[speedBin(D.v[r] * meta.speed_unit_kmh)];
      case 'platoon': {
        if (kind !== 'cav') return HUMAN_FADED;
        const p = platoons(f), g = p.group.get(k);
        if (g === undefined || p.size.get(g) < 2) return NO_PLATOON_CAV;
        return PLATOON[D.tId[g] % PLATOON.length];
      }
      case 'mode': return D.mode[r] === 255 ? HUMAN_FADED : MODE[D.mode[r] % MODE.length];
      case 'regime': return D.regime[r] === 255 ? HUMAN_FADED : MODE[D.regime[r] % MODE.length];
      default: return KIND[kind] || OTHER_KIND;
    }
  }

  // ---- drawing -------------------------------------------------------------------------
  const drawnRects = { k: [], x: [], y: [], w: [], h: [] };

  function drawRoad(f) {
    const t = frames[f];
    ctx.fillStyle = '#fbfbf8';
    ctx.fillRect(0, 0, W, H);
    const top = roadTop, bottom = roadTop + road.lanes * laneH;
    // Control section and PD zone.
    const band = (a, b, y0, y1, style) => {
      const xa = Math.max(-5, sx(a)), xb = Math.min(W + 5, sx(b));
      if (xb > xa) { ctx.fillStyle = style; ctx.fillRect(xa, y0, xb - xa, y1 - y0); }
    };
    band(road.control_m[0], road.control_m[1], top - 12, top - 4, 'rgba(120,120,200,0.35)');
    for (const s of road.segments) {
      const y = laneY(s.lane) - laneH / 2;
      band(s.from_m, s.to_m, y + 1, y + laneH - 1, s.accel ? '#d9d4c4' : '#c9c9c9');
      if (s.ends && sx(s.to_m) > -5 && sx(s.to_m) < W + 5) {
        ctx.fillStyle = '#444';
        ctx.fillRect(sx(s.to_m) - 1, y + 1, 3, laneH - 2);
      }
    }
    if (road.pd_zone_m) {
      const on = t >= road.pd_window_s[0] && t <= road.pd_window_s[1];
      for (const p of road.organized) {
        const y = laneY(p.lane) - laneH / 2;
        band(p.from_m, p.to_m, y + 1, y + laneH - 1, on ? 'rgba(0,150,70,0.22)' : 'rgba(0,150,70,0.08)');
        band(p.from_m, p.to_m, y + 1, y + 3, on ? 'rgba(0,120,60,0.9)' : 'rgba(0,120,60,0.25)');
      }
    }
    // Lane lines between adjacent lanes.
    ctx.strokeStyle = '#fff';
    ctx.lineWidth = 1;
    ctx.setLineDash([6, 6]);
    ctx.beginPath();
    for (let l = 1; l < road.lanes; l++) {
      const y = laneY(l) - laneH / 2;
      ctx.moveTo(0, y); ctx.lineTo(W, y);
    }
    ctx.stroke();
    ctx.setLineDash([]);
    // Ramps: on-ramps join from below on the left of their merge point, off-ramps leave.
    ctx.strokeStyle = '#9a9a9a';
    ctx.lineWidth = 4;
    const ramp = (x, lane, dir) => {
      const y = laneY(lane) + laneH / 2;
      const len = Math.max(24, 300 * S.ppm);
      ctx.beginPath();
      ctx.moveTo(sx(x), y);
      ctx.lineTo(sx(x) + dir * len, y + 22);
      ctx.stroke();
    };
    ctx.font = '11px system-ui, sans-serif';
    for (const r of road.on_ramps) ramp(r.x_m, r.lane, -1);
    for (const r of road.off_ramps) ramp(r.x_m, r.lane, 1);
    ctx.fillStyle = '#555';
    for (const r of road.on_ramps.concat(road.off_ramps)) {
      const x = sx(r.x_m);
      if (x > -40 && x < W + 40) ctx.fillText(r.name, x - 12, bottom + 34);
    }
    // Detectors.
    ctx.strokeStyle = 'rgba(40,40,40,0.7)';
    ctx.lineWidth = 1;
    ctx.setLineDash([2, 2]);
    ctx.beginPath();
    for (const d of road.detectors) {
      if (d.kind !== 'mainline') continue;
      const x = Math.round(sx(d.x_m)) + 0.5;
      if (x < 0 || x > W) continue;
      ctx.moveTo(x, top - 2); ctx.lineTo(x, bottom + 2);
    }
    ctx.stroke();
    ctx.setLineDash([]);
    // Scale: a tick every "nice" distance.
    const step = niceStep(100 / S.ppm);
    ctx.fillStyle = '#444';
    ctx.strokeStyle = '#888';
    ctx.beginPath();
    for (let x = Math.ceil(S.x0 / step) * step; sx(x) < W; x += step) {
      ctx.moveTo(sx(x) + 0.5, 2); ctx.lineTo(sx(x) + 0.5, 8);
      ctx.fillText(fmtDist(x, step), sx(x) + 3, 11);
    }
    ctx.stroke();
    ctx.fillStyle = '#555';
    ctx.fillText('control section', Math.max(2, sx(road.control_m[0]) + 2), top - 15);
  }

  function niceStep(m) {
    const p = Math.pow(10, Math.floor(Math.log10(m)));
    for (const k of [1, 2, 5, 10]) if (k * p >= m) return k * p;
    return 10 * p;
  }
  // Kilometres with as many decimals as the tick step needs.
  const fmtDist = (x, step) => {
    if (step >= 1000 || Math.abs(x) < 1000) return Math.abs(x) < 1000 ? `${x.toFixed(0)} m` : `${(x / 1000).toFixed(0)} km`;
    return `${(x / 1000).toFixed(step >= 100 ? 1 : step >= 10 ? 2 : 3)} km`;
  };

  // Position and lane of track k at time t (between frames f and f + 1 when playing).
  function place(k, f, alpha) {
    const r = rowOf(k, f);
    let x = D.x[r], y = laneY(D.lane[r]);
    if (alpha > 0) {
      const r1 = rowOf(k, f + 1);
      if (r1 >= 0) {
        x += (D.x[r1] - x) * alpha;
        y += (laneY(D.lane[r1]) - y) * alpha;
      }
    }
    return [x, y, r];
  }

  function render() {
    const f = frameAt(S.t);
    const alpha = f < F - 1 && S.playing ? Math.max(0, Math.min(1, (S.t - frames[f]) / (frames[f + 1] - frames[f]))) : 0;
    if (S.follow && S.selected >= 0) {
      const k = trackOfId(S.selected, f);
      if (k >= 0) S.x0 = place(k, f, alpha)[0] - W / 2 / S.ppm;
    }
    drawRoad(f);
    const a = D.frameStart[f], b = D.frameStart[f + 1];
    const ch = carH(), w = Math.max(2, L * S.ppm);
    const rects = drawnRects;
    rects.k.length = rects.x.length = rects.y.length = rects.w.length = rects.h.length = 0;
    let selRect = null;
    const leaders = [];
    const changed = [];
    const batches = new Map();
    const lead = S.colour === 'platoon' ? platoons(f).leader : null;
    for (let i = a; i < b; i++) {
      const k = D.frameTracks[i];
      const [x, yc, r] = place(k, f, alpha);
      const left = sx(x - L);
      if (left > W || left + w < 0) continue;
      const c = css(colourOf(k, r, f));
      const top = yc - ch / 2;
      let batch = batches.get(c);
      if (!batch) { batch = []; batches.set(c, batch); }
      batch.push(left, top);
      rects.k.push(k); rects.x.push(left); rects.y.push(top); rects.w.push(w); rects.h.push(ch);
      if (D.tId[k] === S.selected) selRect = [left, top, w, ch];
      if (lead && lead.has(k)) leaders.push([left + w, yc]);
      if (alpha === 0) {
        const rp = rowOf(k, f - 1);
        if (rp >= 0 && D.lane[rp] !== D.lane[r]) changed.push([left + w / 2, laneY(D.lane[rp]), yc]);
      }
    }
    // One path per colour: far fewer state changes than one fill per vehicle.
    for (const [c, xy] of batches) {
      ctx.fillStyle = c;
      ctx.beginPath();
      for (let j = 0; j < xy.length; j += 2) ctx.rect(xy[j], xy[j + 1], w, ch);
      ctx.fill();
    }
    // Platoon leaders: a dark wedge at the front.
    ctx.fillStyle = '#111';
    for (const [x, y] of leaders) {
      ctx.beginPath();
      ctx.moveTo(x + 1, y - ch / 2 - 1); ctx.lineTo(x + 5, y); ctx.lineTo(x + 1, y + ch / 2 + 1);
      ctx.fill();
    }
    // Lane changes since the previous frame: a line from the old lane.
    ctx.strokeStyle = 'rgba(0,0,0,0.6)';
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    for (const [x, y0, y1] of changed) { ctx.moveTo(x, y0); ctx.lineTo(x, y1); }
    ctx.stroke();
    // Collisions within 5 s of now.
    ctx.strokeStyle = '#d00';
    ctx.lineWidth = 2;
    for (const c of meta.collisions) {
      if (Math.abs(c.t_s - frames[f]) > 5) continue;
      const x = sx(c.x_m), y = laneY(c.lane);
      ctx.beginPath();
      ctx.moveTo(x - 6, y - 6); ctx.lineTo(x + 6, y + 6); ctx.moveTo(x + 6, y - 6); ctx.lineTo(x - 6, y + 6);
      ctx.stroke();
    }
    if (selRect) {
      ctx.strokeStyle = '#000';
      ctx.lineWidth = 2;
      ctx.strokeRect(selRect[0] - 2, selRect[1] - 2, selRect[2] + 4, selRect[3] + 4);
    }
    S.drawn = rects.k.length;
    drawMini(f);
    drawContourMarks(f);
    el('clock').textContent = `t = ${frames[f].toFixed(1)} s (${fmtClock(frames[f])})  ${S.drawn} drawn`;
    el('slider').value = String(f);
    showVehicle(f);
  }

  const fmtClock = (t) => {
    const s = Math.floor(t), h = Math.floor(s / 3600), m = Math.floor((s % 3600) / 60);
    return `${h}:${String(m).padStart(2, '0')}:${String(s % 60).padStart(2, '0')}`;
  };

  function drawMini(f) {
    const mw = mini.getBoundingClientRect().width, mh = mini.getBoundingClientRect().height;
    const span = road.end_m - road.start_m;
    const mx = (x) => 4 + (x - road.start_m) / span * (mw - 8);
    mctx.fillStyle = '#fff';
    mctx.fillRect(0, 0, mw, mh);
    const lh = Math.max(2, Math.floor((mh - 8) / road.lanes));
    const my = (lane) => 4 + (road.lanes - lane) * lh;
    mctx.fillStyle = '#ddd';
    for (const s of road.segments) mctx.fillRect(mx(s.from_m), my(s.lane), mx(s.to_m) - mx(s.from_m), lh - 1);
    const a = D.frameStart[f], b = D.frameStart[f + 1];
    const batches = new Map();
    for (let i = a; i < b; i++) {
      const k = D.frameTracks[i], r = rowOf(k, f);
      const c = css(colourOf(k, r, f));
      let batch = batches.get(c);
      if (!batch) { batch = []; batches.set(c, batch); }
      batch.push(mx(D.x[r]) - 1, my(D.lane[r]));
    }
    for (const [c, xy] of batches) {
      mctx.fillStyle = c;
      mctx.beginPath();
      for (let j = 0; j < xy.length; j += 2) mctx.rect(xy[j], xy[j + 1], 2, lh - 1);
      mctx.fill();
    }
    mctx.strokeStyle = '#000';
    mctx.lineWidth = 1.5;
    mctx.strokeRect(mx(S.x0), 1, Math.max(3, W / S.ppm / span * (mw - 8)), mh - 2);
  }

  // ---- speed contour -------------------------------------------------------------------
  const C = meta.contour;
  const contourImage = (() => {
    const img = cctx.createImageData(C.nt, C.nx);
    for (let it = 0; it < C.nt; it++) {
      for (let ix = 0; ix < C.nx; ix++) {
        const v = D.contour[it * C.nx + ix];
        const p = ((C.nx - 1 - ix) * C.nt + it) * 4;
        const c = v === 255 ? [235, 235, 235] : SPEED[speedBin(v * meta.speed_unit_kmh)];
        img.data[p] = c[0]; img.data[p + 1] = c[1]; img.data[p + 2] = c[2]; img.data[p + 3] = 255;
      }
    }
    const off = document.createElement('canvas');
    off.width = C.nt; off.height = C.nx;
    off.getContext('2d').putImageData(img, 0, 0);
    return off;
  })();
  function drawContourMarks(f) {
    const cw = contour.width, chh = contour.height;
    cctx.imageSmoothingEnabled = false;
    cctx.drawImage(contourImage, 0, 0, cw, chh);
    const span = C.t1_s - C.t0_s || 1, xspan = C.x1_m - C.x0_m;
    const tx = (frames[f] - C.t0_s) / span * cw;
    cctx.strokeStyle = '#000';
    cctx.lineWidth = 1;
    cctx.beginPath(); cctx.moveTo(tx + 0.5, 0); cctx.lineTo(tx + 0.5, chh); cctx.stroke();
    const ya = chh - (S.x0 - C.x0_m) / xspan * chh, yb = chh - (S.x0 + W / S.ppm - C.x0_m) / xspan * chh;
    cctx.strokeStyle = 'rgba(0,0,0,0.8)';
    cctx.strokeRect(0.5, Math.max(0, yb), cw - 1, Math.max(2, Math.min(chh, ya) - Math.max(0, yb)));
  }
  contour.addEventListener('click', (e) => {
    const r = contour.getBoundingClientRect();
    const fx = (e.clientX - r.left) / r.width, fy = (e.clientY - r.top) / r.height;
    setTime(C.t0_s + fx * (C.t1_s - C.t0_s));
    const x = C.x0_m + (1 - fy) * (C.x1_m - C.x0_m);
    S.follow = false; el('follow').checked = false;
    S.x0 = x - W / 2 / S.ppm;
    clampView();
    render();
  });

  // ---- vehicle panel and legend --------------------------------------------------------
  const tripIndex = new Map(meta.trips.id.map((id, i) => [id, i]));
  function showVehicle(f) {
    const box = el('vehicle');
    if (S.selected < 0) return;
    const k = trackOfId(S.selected, f);
    const rows = [['id', String(S.selected)]];
    if (k < 0) {
      rows.push(['', 'not on the road at this time']);
    } else {
      const r = rowOf(k, f);
      rows.push(['kind', kindName(k)], ['lane', String(D.lane[r])],
        ['speed', `${(D.v[r] * meta.speed_unit_kmh).toFixed(1)} km/h`]);
      if (meta.accel_column) rows.push(['acceleration', `${(D.a[r] * meta.accel_unit).toFixed(1)} m/s²`]);
      rows.push(['position', `${D.x[r].toFixed(1)} m`]);
      if (D.mode[r] !== 255) rows.push(['mode', meta.modes[D.mode[r]]]);
      if (D.regime[r] !== 255) rows.push(['regime', meta.regimes[D.regime[r]]]);
      const p = platoons(f), g = p.group.get(k), n = g === undefined ? 1 : p.size.get(g);
      if (kindName(k) === 'cav') {
        const where = meta.platoon_column ? `position ${D.pos[r]}` : 'inferred';
        rows.push(['platoon', n > 1 ? `${n} vehicles led by ${D.tId[g]} (${where})` : 'none (drives alone)']);
      }
    }
    const ti = tripIndex.get(S.selected);
    if (ti !== undefined) {
      const tr = meta.trips;
      rows.push(['origin', tr.origin[ti] || '-'], ['destination', tr.destination[ti] || 'still on the road']);
      const t0 = tr.entered_s[ti];
      if (t0 !== null) {
        const now = frames[f], end = tr.left_s[ti];
        const tt = end !== null && end <= now ? `${(end - t0).toFixed(1)} s (trip ended)` : `${Math.max(0, now - t0).toFixed(1)} s so far`;
        rows.push(['entered', `${t0.toFixed(1)} s`], ['travel time', tt]);
      }
    } else if (meta.trips.id.length === 0) {
      rows.push(['trip', 'no trips.csv in the run (run with --trips)']);
    }
    // Cells by textContent: trips.csv and trajectories.csv strings are data, never markup.
    const table = document.createElement('table');
    for (const [a, b] of rows) {
      const tr = table.insertRow();
      tr.insertCell().textContent = a;
      tr.insertCell().textContent = b;
    }
    box.replaceChildren(table);
  }

  function legend() {
    // Names from the run's files (modes, regimes) are escaped; the rest is the page's own.
    const sw = (c, text) => `<div><span class="sw" style="background:${css(c)}"></span>${esc(text)}</div>`;
    let h = '';
    if (S.colour === 'kind') {
      h += sw(KIND.cav, 'CAV') + sw(KIND.human, 'human-driven');
    } else if (S.colour === 'speed') {
      const stops = [];
      for (let b = 0; b < SPEED_BINS; b++) stops.push(`${css(SPEED[b])} ${(b / SPEED_BINS * 100).toFixed(1)}% ${((b + 1) / SPEED_BINS * 100).toFixed(1)}%`);
      h += `<div><span class="bar" style="background:linear-gradient(to right, ${stops.join(',')})"></span></div>`;
      h += '<div class="note">0 to 120 km/h in 5 km/h steps (the scale of the project\'s plots)</div>';
    } else if (S.colour === 'platoon') {
      h += sw(PLATOON[0], 'one colour per CACC string (a wedge marks its leader)');
      h += sw(NO_PLATOON_CAV, 'CAV not in a string') + sw(HUMAN_FADED, 'human-driven');
      h += meta.platoon_column
        ? '<div class="note">strings from the platoon_pos column of trajectories.csv</div>'
        : '<div class="note"><b>inferred</b>: consecutive CAVs in a lane within a 2 s time gap (this trajectories.csv has no platoon_pos column)</div>';
    } else {
      const names = S.colour === 'mode' ? meta.modes : meta.regimes;
      names.forEach((m, i) => { h += sw(MODE[i % MODE.length], m); });
      h += sw(HUMAN_FADED, S.colour === 'mode' ? 'no mode recorded' : 'no regime (human or manual)');
    }
    h += '<div class="note" style="margin-top:6px">road: grey lanes, beige acceleration lanes, dark bar = lane end, '
      + 'slanted stubs = ramps, blue band = control section'
      + (road.pd_zone_m ? `, green = ${road.strategy === 'dedicated' ? 'dedicated' : 'PD'} lane in its zone (brighter while active)` : '')
      + ', dashed = detectors; vehicles ' + L.toFixed(1) + ' m long'
      + (meta.collisions.length ? `; <b style="color:#d00">${meta.collisions.length} collisions</b> (red X)` : '') + '</div>';
    el('legend').innerHTML = h;
  }

  // ---- time and controls ---------------------------------------------------------------
  function setTime(t) {
    S.t = frames[frameAt(t)];
  }
  function play(on) {
    S.playing = on && F > 1;
    el('play').textContent = S.playing ? 'Pause' : 'Play';
    S.lastWall = performance.now();
    if (S.playing) requestAnimationFrame(tick);
    else { setTime(S.t); render(); }
  }
  function tick(now) {
    if (!S.playing) return;
    const dt = Math.min(0.25, (now - S.lastWall) / 1000);
    S.lastWall = now;
    S.t += dt * S.speed;
    if (S.t >= frames[F - 1]) { S.t = frames[F - 1]; render(); play(false); return; }
    S.rafFrames++;
    render();
    requestAnimationFrame(tick);
  }
  function step(n) {
    S.playing = false;
    el('play').textContent = 'Play';
    S.t = frames[Math.max(0, Math.min(F - 1, frameAt(S.t) + n))];
    render();
  }
  function setSpeed(s) {
    S.speed = s;
    el('speed').value = String(s);
  }
  function setColour(c) {
    S.colour = c;
    el('colour').value = c;
    legend();
    render();
  }
  function select(id) {
    S.selected = id;
    if (id < 0) { el('vehicle').textContent = 'Click a vehicle to see it; F follows it.'; S.follow = false; el('follow').checked = false; }
    render();
  }
  function zoom(factor, cx) {
    const xm = S.x0 + cx / S.ppm;
    S.ppm *= factor;
    clampView();
    S.x0 = xm - cx / S.ppm;
    clampView();
    render();
  }

  el('play').onclick = () => play(!S.playing);
  el('back').onclick = () => step(-1);
  el('fwd').onclick = () => step(1);
  el('speed').onchange = (e) => setSpeed(Number(e.target.value));
  el('colour').onchange = (e) => setColour(e.target.value);
  el('follow').onchange = (e) => { S.follow = e.target.checked; render(); };
  el('slider').max = String(F - 1);
  el('slider').oninput = (e) => { S.t = frames[Number(e.target.value)]; render(); };

  // Pan by dragging; a click without movement selects.
  let drag = null;
  canvas.addEventListener('mousedown', (e) => { drag = { x: e.clientX, x0: S.x0, moved: false }; });
  window.addEventListener('mouseup', (e) => {
    if (drag && !drag.moved) pick(e);
    drag = null;
  });
  canvas.addEventListener('mousemove', (e) => {
    if (drag) {
      if (Math.abs(e.clientX - drag.x) > 3) drag.moved = true;
      if (drag.moved) {
        S.follow = false; el('follow').checked = false;
        S.x0 = drag.x0 - (e.clientX - drag.x) / S.ppm; clampView(); render();
      }
      return;
    }
    hoverDetector(e);
  });
  canvas.addEventListener('mouseleave', () => { el('tip').hidden = true; });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    const r = canvas.getBoundingClientRect();
    zoom(e.deltaY < 0 ? 1.25 : 0.8, e.clientX - r.left);
  }, { passive: false });

  function pick(e) {
    const r = canvas.getBoundingClientRect();
    const px = e.clientX - r.left, py = e.clientY - r.top;
    let best = -1, bestD = 5;
    const R = drawnRects;
    for (let i = 0; i < R.k.length; i++) {
      const dx = Math.max(R.x[i] - px, 0, px - (R.x[i] + R.w[i]));
      const dy = Math.max(R.y[i] - py, 0, py - (R.y[i] + R.h[i]));
      const d = Math.hypot(dx, dy);
      if (d < bestD) { bestD = d; best = R.k[i]; }
    }
    if (best >= 0) select(D.tId[best]);
  }

  function hoverDetector(e) {
    const r = canvas.getBoundingClientRect();
    const px = e.clientX - r.left, py = e.clientY - r.top;
    const tip = el('tip');
    const bottom = roadTop + road.lanes * laneH;
    let hit = null;
    if (py >= roadTop - 4 && py <= bottom + 4) {
      for (const d of road.detectors) {
        if (d.kind === 'mainline' && Math.abs(sx(d.x_m) - px) <= 3) { hit = d; break; }
      }
    }
    if (!hit) { tip.hidden = true; return; }
    const t = S.t;
    const series = meta.detectors.find((d) => d.name === hit.name) || { start_s: [] };
    let i = -1;
    for (let j = 0; j < series.start_s.length; j++) {
      if (series.start_s[j] <= t && t < series.start_s[j] + series.interval_s[j]) { i = j; break; }
    }
    let text = `detector ${hit.name} at ${hit.x_m.toFixed(0)} m`;
    if (i < 0) {
      text += meta.detectors.length ? '\nno complete interval at this time' : '\nno detectors.csv in the run';
    } else {
      const q = series.flow_vph[i], v = series.speed_kmh[i];
      const per = series.lanes > 0 ? ` (${(q / series.lanes).toFixed(0)} veh/h/lane over ${series.lanes} lanes)` : '';
      text += `\n${series.start_s[i].toFixed(0)}-${(series.start_s[i] + series.interval_s[i]).toFixed(0)} s: ${q.toFixed(0)} veh/h${per}`;
      text += `\nspeed ${v === null ? '- (no vehicle)' : v.toFixed(1) + ' km/h'}`;
    }
    tip.textContent = text;
    tip.hidden = false;
    tip.style.left = `${Math.min(px + 12, W - 260)}px`;
    tip.style.top = `${py + 12}px`;
  }

  function miniJump(e) {
    const r = mini.getBoundingClientRect();
    const span = road.end_m - road.start_m;
    const x = road.start_m + (e.clientX - r.left - 4) / (r.width - 8) * span;
    S.follow = false; el('follow').checked = false;
    S.x0 = x - W / 2 / S.ppm; clampView(); render();
  }
  let miniDrag = false;
  mini.addEventListener('mousedown', (e) => { miniDrag = true; miniJump(e); });
  mini.addEventListener('mousemove', (e) => { if (miniDrag) miniJump(e); });
  window.addEventListener('mouseup', () => { miniDrag = false; });

  const SPEEDS = [1, 2, 4, 8, 16, 32, 64];
  window.addEventListener('keydown', (e) => {
    if (e.target.tagName === 'INPUT' && e.target.type !== 'range' && e.target.type !== 'checkbox') return;
    const pan = (frac) => { S.follow = false; el('follow').checked = false; S.x0 += frac * W / S.ppm; clampView(); render(); };
    switch (e.key) {
      case ' ': play(!S.playing); break;
      case ',': step(-1); break;
      case '.': step(1); break;
      case '[': setSpeed(SPEEDS[Math.max(0, SPEEDS.indexOf(S.speed) - 1)]); break;
      case ']': setSpeed(SPEEDS[Math.min(SPEEDS.length - 1, SPEEDS.indexOf(S.speed) + 1)]); break;
      case 'Home': step(-F); break;
      case 'End': step(F); break;
      case 'ArrowLeft': if (e.shiftKey) step(-1); else pan(-0.25); break;
      case 'ArrowRight': if (e.shiftKey) step(1); else pan(0.25); break;
      case '+': case '=': zoom(1.5, W / 2); break;
      case '-': case '_': zoom(1 / 1.5, W / 2); break;
      case '0': fitAll(); render(); break;
      case 'c': case 'C': setColour(colourModes[(colourModes.indexOf(S.colour) + 1) % colourModes.length]); break;
      case 'f': case 'F': S.follow = !S.follow && S.selected >= 0; el('follow').checked = S.follow; render(); break;
      case 'Escape': select(-1); break;
      default: return;
    }
    e.preventDefault();
  });
  window.addEventListener('resize', () => { resize(); clampView(); render(); });

  el('title').textContent = `${road.name}` + (road.penetration !== null ? `, ${(road.penetration * 100).toFixed(0)} % CAV` : '')
    + `, strategy ${road.strategy}` + (road.seed !== null ? `, seed ${road.seed}` : '')
    + ` | ${meta.rows.toLocaleString('en')} samples, ${frames.length} frames`;
  resize();
  fitAll();
  legend();
  render();

  // ---- test hooks (used by the browser tests in tests/browser) --------------------------
  window.__platoonsimView = {
    ready: true,
    frames: () => frames.slice(),
    time: () => S.t,
    frame: () => frameAt(S.t),
    setTime: (t) => { setTime(t); render(); },
    play: () => play(true),
    pause: () => play(false),
    playing: () => S.playing,
    setSpeed,
    setColour,
    select,
    selected: () => S.selected,
    // The view transform: a vehicle with front at x (m) in lane l is drawn from screen x
    // canvasLeft + (x - length - x0_m) * px_per_m, centred on canvasTop + laneY(l).
    setView: (x0, ppm) => { S.follow = false; S.ppm = ppm; S.x0 = x0; render(); },
    view: () => {
      const r = canvas.getBoundingClientRect();
      const lanes = {};
      for (let l = 1; l <= road.lanes; l++) lanes[l] = laneY(l);
      return { x0_m: S.x0, px_per_m: S.ppm, canvasLeft: r.left, canvasTop: r.top, width: W,
        laneCentreY: lanes, carHeight: carH(), vehicleLength: L, minWidth: 2 };
    },
    // The rectangle drawn for vehicle `id` in the last frame (page coordinates), or null.
    vehicleRect: (id) => {
      const r = canvas.getBoundingClientRect();
      const R = drawnRects;
      for (let i = 0; i < R.k.length; i++) {
        if (D.tId[R.k[i]] === id) return { x: r.left + R.x[i], y: r.top + R.y[i], w: R.w[i], h: R.h[i] };
      }
      return null;
    },
    colour: (id) => {
      const f = frameAt(S.t), k = trackOfId(id, f);
      return k < 0 ? null : colourOf(k, rowOf(k, f), f);
    },
    drawnCount: () => S.drawn,
    rafFrames: () => S.rafFrames,
    // Mean time of one full render (road, vehicles, minimap, contour) over n frames, in ms.
    benchmark: (n) => {
      const f0 = frameAt(S.t);
      const t0 = performance.now();
      for (let i = 0; i < n; i++) { S.t = frames[Math.min(F - 1, f0 + (i % 2))]; render(); }
      const ms = (performance.now() - t0) / n;
      S.t = frames[f0]; render();
      return ms;
    },
  };
})().catch((e) => {
  document.body.insertAdjacentHTML('afterbegin', '<pre style="color:#b00;padding:8px"></pre>');
  document.body.firstChild.textContent = 'platoonsim view: cannot show this run: ' + e;
  throw e;
});

// Inflates the gzip+base64 block and splits it into the typed arrays listed in meta.sections,
// then decodes positions (second differences) and indexes the rows by frame.
async function unpack(meta, b64) {
  const bin = atob(b64);
  const gz = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) gz[i] = bin.charCodeAt(i);
  const stream = new Blob([gz]).stream().pipeThrough(new DecompressionStream('gzip'));
  const buf = await new Response(stream).arrayBuffer();
  const sec = {};
  let at = 0;
  for (const s of meta.sections) {
    at = (at + 3) & ~3;
    const T = s.type === 'u32' ? Uint32Array : s.type === 'i32' ? Int32Array : Uint8Array;
    sec[s.name] = new T(buf, at, s.len);
    at += s.len * T.BYTES_PER_ELEMENT;
  }
  const nT = meta.tracks, R = meta.rows, F = meta.frames.length;
  const rowStart = new Uint32Array(nT + 1);
  for (let k = 0; k < nT; k++) rowStart[k + 1] = rowStart[k] + sec.track_len[k];
  const x = new Float32Array(R);
  const lo = sec.ddx_lo, hi = sec.ddx_hi, res = meta.x_res_m;
  for (let k = 0; k < nT; k++) {
    let q = sec.track_x0[k], dq = 0;
    for (let r = rowStart[k]; r < rowStart[k + 1]; r++) {
      let dd = lo[r] | (hi[r] << 8);
      if (dd & 0x8000) dd -= 0x10000;
      dq += dd;
      q += dq;
      x[r] = q * res;
    }
  }
  const frameStart = new Uint32Array(F + 1);
  for (let k = 0; k < nT; k++) {
    const f0 = sec.track_first[k];
    for (let f = f0; f < f0 + sec.track_len[k]; f++) frameStart[f + 1]++;
  }
  for (let f = 0; f < F; f++) frameStart[f + 1] += frameStart[f];
  const fill = frameStart.slice(0, F);
  const frameTracks = new Uint32Array(R);
  for (let k = 0; k < nT; k++) {
    const f0 = sec.track_first[k];
    for (let f = f0; f < f0 + sec.track_len[k]; f++) frameTracks[fill[f]++] = k;
  }
  const tracksById = new Map();
  for (let k = 0; k < nT; k++) {
    const id = sec.track_id[k];
    if (!tracksById.has(id)) tracksById.set(id, []);
    tracksById.get(id).push(k);
  }
  return {
    tId: sec.track_id, tFirst: sec.track_first, tLen: sec.track_len, tKind: sec.track_kind,
    rowStart, x, v: sec.v, a: new Int8Array(sec.a.buffer, sec.a.byteOffset, sec.a.length),
    lane: sec.lane, mode: sec.mode, pos: sec.pos, regime: sec.regime, contour: sec.contour,
    frameStart, frameTracks, tracksById,
  };
}
