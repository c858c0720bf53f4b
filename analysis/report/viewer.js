// kneesim report viewer (inlined into report.html by analysis/report/report_page.cpp).
// Draws the insert coloured by the chosen field at the slider's step and the femoral
// component posed at that step, with three.js (Debian libjs-three, inlined before this file).
// Renders on demand only (no animation loop). With "#selfcheck" in the address it renders,
// moves the slider, measures the canvas and writes the findings as JSON into
// <pre id="kneesim-selfcheck"> (tests/report/report_browser_test.py reads them).
(function () {
  'use strict';
  var check = { webgl: false, scene: false, numbers: [] };
  var api = null;

  function b64(s, Type) {
    var bin = atob(s), u = new Uint8Array(bin.length);
    for (var i = 0; i < bin.length; i++) u[i] = bin.charCodeAt(i);
    return new Type(u.buffer);
  }

  // sequential map: light grey (zero) through yellow and orange to dark red
  var STOPS = [[0.00, [0.86, 0.87, 0.89]], [0.15, [0.99, 0.93, 0.55]], [0.40, [0.99, 0.68, 0.24]],
               [0.65, [0.91, 0.33, 0.13]], [0.85, [0.70, 0.09, 0.12]], [1.00, [0.40, 0.00, 0.05]]];
  var NO_VALUE = [0.62, 0.64, 0.68];
  function colour(u) {
    for (var i = 1; i < STOPS.length; i++) {
      if (u <= STOPS[i][0]) {
        var a = STOPS[i - 1], b = STOPS[i], t = (u - a[0]) / (b[0] - a[0]);
        return [a[1][0] + t * (b[1][0] - a[1][0]), a[1][1] + t * (b[1][1] - a[1][1]),
                a[1][2] + t * (b[1][2] - a[1][2])];
      }
    }
    return STOPS[STOPS.length - 1][1];
  }
  function fmt(v) {
    var a = Math.abs(v);
    return a === 0 ? '0' : a >= 100 ? v.toFixed(0) : a >= 10 ? v.toFixed(1) : a >= 1 ? v.toFixed(2) : v.toPrecision(3);
  }

  function geometry(m) {
    var g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(b64(m.positions, Float32Array), 3));
    g.setIndex(new THREE.BufferAttribute(b64(m.triangles, Uint32Array), 1));
    g.computeVertexNormals();
    return g;
  }

  function setup() {
    var el = document.getElementById('kneesim-scene');
    if (!el || typeof THREE === 'undefined') return null;
    check.scene = true;
    var S = JSON.parse(el.textContent);
    var canvas = document.getElementById('kneesim-canvas');
    var probe = document.createElement('canvas');
    if (!(probe.getContext('webgl') || probe.getContext('experimental-webgl'))) {
      canvas.insertAdjacentHTML('afterend', '<p class="note">This browser offers no WebGL: the 3D view cannot be drawn.</p>');
      return null;
    }
    var renderer = new THREE.WebGLRenderer({ canvas: canvas, antialias: true, preserveDrawingBuffer: true });
    check.webgl = true;
    renderer.setPixelRatio(1);
    renderer.setSize(canvas.clientWidth || 760, canvas.clientHeight || 500, false);
    renderer.setClearColor(0xfafafa, 1);
    var scene = new THREE.Scene();
    scene.add(new THREE.AmbientLight(0xffffff, 0.55));
    var sun = new THREE.DirectionalLight(0xffffff, 0.55);
    sun.position.set(0.6, 1.0, 0.8);
    scene.add(sun);

    // insert: per-face colours need one vertex per face corner (normals stay smooth)
    var ins = geometry(S.insert).toNonIndexed();
    var nfaces = S.insert.faces;
    var colours = new Float32Array(nfaces * 9);
    ins.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    var insertMesh = new THREE.Mesh(ins, new THREE.MeshLambertMaterial({ vertexColors: THREE.VertexColors, side: THREE.DoubleSide }));
    scene.add(insertMesh);

    var femurMesh = null, poses = null;
    if (S.femur) {
      femurMesh = new THREE.Mesh(geometry(S.femur), new THREE.MeshPhongMaterial({
        color: 0x9aa6b8, transparent: true, opacity: 0.35, depthWrite: false, shininess: 40 }));
      femurMesh.matrixAutoUpdate = false;
      poses = b64(S.femur_poses, Float32Array);
      scene.add(femurMesh);
    }

    ins.computeBoundingBox();
    var box = ins.boundingBox, centre = new THREE.Vector3(), size = new THREE.Vector3();
    box.getCenter(centre);
    box.getSize(size);
    var r = Math.max(size.x, size.y, size.z);
    var camera = new THREE.PerspectiveCamera(35, canvas.clientWidth / canvas.clientHeight || 1.52, r / 50, r * 50);
    camera.position.set(centre.x + 0.9 * r, centre.y + 1.2 * r, centre.z + 0.75 * r);
    var controls = new THREE.OrbitControls(camera, canvas);
    controls.target.copy(centre);
    controls.update();

    var fieldSel = document.getElementById('kneesim-field');
    S.fields.forEach(function (f, i) {
      var o = document.createElement('option');
      o.value = i;
      o.textContent = f.name + ' (' + f.unit + ')';
      fieldSel.appendChild(o);
    });
    var fieldValues = S.fields.map(function (f) { return b64(f.values, Uint8Array); });
    var fieldFaces = S.fields.map(function (f) { return b64(f.faces, Uint32Array); });
    var slider = document.getElementById('kneesim-slider');
    slider.max = String(Math.max(0, S.step_values.length - 1));
    slider.value = String(S.initial_step);
    document.getElementById('kneesim-step-name').textContent = S.step_name;
    var cbar = document.getElementById('kneesim-cbar');
    cbar.style.background = 'linear-gradient(to right,' + STOPS.map(function (s) {
      return 'rgb(' + s[1].map(function (c) { return Math.round(255 * c); }).join(',') + ') ' + (100 * s[0]) + '%';
    }).join(',') + ')';

    function render() { renderer.render(scene, camera); }
    controls.addEventListener('change', render);

    function update() {
      var k = +slider.value, fi = +fieldSel.value || 0, f = S.fields[fi];
      var step = S.step_values[k];
      var shown = Math.abs(step) >= 10000 ? step.toLocaleString('en-US').replace(/,/g, '\u2009')
                                          : String(Math.round(step * 100) / 100);
      document.getElementById('kneesim-step').textContent = shown + (S.step_unit ? ' ' + S.step_unit : '');
      if (f) {
        var q = fieldValues[fi], faces = fieldFaces[fi], n = f.face_count, off = k * n;
        for (var i = 0; i < colours.length; i += 3) {
          colours[i] = NO_VALUE[0]; colours[i + 1] = NO_VALUE[1]; colours[i + 2] = NO_VALUE[2];
        }
        for (var j = 0; j < n; j++) {
          var b = q[off + j], c = b === 255 ? NO_VALUE : colour(b / 254), i9 = 9 * faces[j];
          for (var v = 0; v < 3; v++) {
            colours[i9 + 3 * v] = c[0]; colours[i9 + 3 * v + 1] = c[1]; colours[i9 + 3 * v + 2] = c[2];
          }
        }
        ins.attributes.color.needsUpdate = true;
        document.getElementById('kneesim-legend-title').textContent = f.name + ' (' + f.unit + ')';
        document.getElementById('kneesim-legend-min').textContent = fmt(f.min);
        document.getElementById('kneesim-legend-max').textContent = fmt(f.max);
        document.getElementById('kneesim-step-max').textContent =
          'largest at this ' + S.step_name + ': ' + fmt(f.step_max[k]) + ' ' + f.unit + '; grey: no value';
      }
      if (femurMesh) {
        var p = S.femur_pose_count > 1 ? Math.min(k, S.femur_pose_count - 1) : 0;
        femurMesh.matrix.fromArray(poses, 16 * p);
        femurMesh.visible = document.getElementById('kneesim-femur').checked;
      }
      render();
    }
    slider.addEventListener('input', update);
    fieldSel.addEventListener('change', update);
    document.getElementById('kneesim-femur').addEventListener('change', update);
    update();
    return { renderer: renderer, slider: slider, update: update, S: S };
  }

  function grab() {
    var gl = api.renderer.getContext();
    var w = gl.drawingBufferWidth, h = gl.drawingBufferHeight, px = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    return { w: w, h: h, px: px };
  }
  function variance(g) {
    var n = g.w * g.h, s = 0, s2 = 0;
    for (var i = 0; i < n; i++) {
      var l = 0.299 * g.px[4 * i] + 0.587 * g.px[4 * i + 1] + 0.114 * g.px[4 * i + 2];
      s += l; s2 += l * l;
    }
    var m = s / n;
    return s2 / n - m * m;
  }
  function changed(a, b) {
    var n = a.w * a.h, c = 0;
    for (var i = 0; i < n; i++) {
      if (a.px[4 * i] !== b.px[4 * i] || a.px[4 * i + 1] !== b.px[4 * i + 1] || a.px[4 * i + 2] !== b.px[4 * i + 2]) c++;
    }
    return c / n;
  }

  function selfcheck() {
    if (api) {
      var a = grab();
      var rect = document.getElementById('kneesim-canvas').getBoundingClientRect();
      check.canvas = { width: a.w, height: a.h, variance: variance(a),
                       rect: [rect.left + window.scrollX, rect.top + window.scrollY, rect.width, rect.height] };
      var s = api.S, from = +api.slider.value, to = from, best = -1;
      // the step whose field maximum differs most from the current one (a visible change)
      if (s.fields.length) {
        var f = s.fields[0];
        for (var k = 0; k < s.step_values.length; k++) {
          var d = Math.abs(f.step_max[k] - f.step_max[from]);
          if (d > best) { best = d; to = k; }
        }
      } else {
        to = from === 0 ? Math.min(1, s.step_values.length - 1) : 0;
      }
      api.slider.value = String(to);
      api.slider.dispatchEvent(new Event('input'));
      var b = grab();
      check.slider = { from: from, to: to, steps: s.step_values.length, changed_fraction: changed(a, b) };
      api.slider.value = String(from);
      api.slider.dispatchEvent(new Event('input'));
    }
    document.querySelectorAll('[data-key]').forEach(function (e) {
      check.numbers.push({ key: e.getAttribute('data-key'), scale: +e.getAttribute('data-scale'), text: e.textContent });
    });
    // everything the page fetched (a self-contained page fetches nothing)
    check.resources = performance.getEntriesByType('resource').map(function (e) { return e.name; });
    check.errors = window.__kneesimErrors || [];
    document.getElementById('kneesim-selfcheck').textContent = JSON.stringify(check);
  }

  try {
    api = setup();
  } catch (e) {
    (window.__kneesimErrors = window.__kneesimErrors || []).push('viewer: ' + e);
    console.error(e);
  }
  if (location.hash.indexOf('selfcheck') >= 0) selfcheck();
})();
