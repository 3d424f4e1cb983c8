// The report page's viewer (view/html_page.h says what it shows and which hooks it
// offers to tests). Reads the scene inlined as JSON (format: view/scene.h) and draws
// it with three.js r111: one renderer, one camera and one orbit control shared by all
// models, each model in its own viewport, so the views before and after stay linked.
(function () {
  'use strict';
  var timing = { start: performance.now() };  // since navigation: the page read and its scripts parsed
  var scene = JSON.parse(document.getElementById('scene').textContent);
  timing.parsed = performance.now();  // the scene's JSON parsed
  var params = new URLSearchParams(window.location.search);
  var still = params.get('still') === '1';
  if (still) document.body.classList.add('still');
  // ?size=WxH: the page laid out at exactly that size, whatever the window (a headless
  // browser lays the page out in a smaller window than the picture it then takes).
  var fixed = /^(\d+)x(\d+)$/.exec(params.get('size') || '');
  if (fixed) {
    var main = document.getElementById('main');
    main.style.width = fixed[1] + 'px';
    main.style.height = fixed[2] + 'px';
  }
  if (!document.body.hasAttribute('data-errors')) document.body.setAttribute('data-errors', '0');

  // ---- data ------------------------------------------------------------------------
  function bytes(b64) {
    if (Uint8Array.fromBase64) return Uint8Array.fromBase64(b64).buffer;  // native where the browser has it
    var s = atob(b64), out = new Uint8Array(s.length);
    for (var i = 0; i < s.length; ++i) out[i] = s.charCodeAt(i);
    return out.buffer;
  }
  function u16(b64) { return new Uint16Array(bytes(b64)); }
  function u32(b64) { return new Uint32Array(bytes(b64)); }
  function colourOf(type) { return new THREE.Color(scene.colors[type] || '#808080'); }
  var size = scene.size > 0 ? scene.size : 1;

  function el(tag, cls, text) {
    var e = document.createElement(tag);
    if (cls) e.className = cls;
    if (text !== undefined) e.textContent = text;
    return e;
  }
  function num(x) { return Number(x).toPrecision(3); }

  // A round dot with a dark rim, multiplied by each point's colour.
  function dotTexture() {
    var c = document.createElement('canvas');
    c.width = c.height = 64;
    var g = c.getContext('2d');
    g.fillStyle = '#222';
    g.beginPath(); g.arc(32, 32, 31, 0, 2 * Math.PI); g.fill();
    g.fillStyle = '#fff';
    g.beginPath(); g.arc(32, 32, 24, 0, 2 * Math.PI); g.fill();
    var t = new THREE.CanvasTexture(c);
    t.minFilter = THREE.LinearFilter;
    return t;
  }
  var dot = dotTexture();

  // ---- models ----------------------------------------------------------------------
  var base = new THREE.Color(0xc9ccd1);
  var base8 = [Math.round(255 * base.r), Math.round(255 * base.g), Math.round(255 * base.b)];
  // Positions arrive as 16-bit grid coordinates (view/scene.h): drawn as a normalised
  // attribute (0..1), which the object's scale and offset put back in place.
  // three.js r111 computes bounding spheres from the raw integers, which would cull
  // these objects wrongly: they are never culled (the model is mostly in view anyway).
  function onGrid(o) {
    o.position.fromArray(scene.grid.low);
    o.scale.setScalar(scene.grid.step * 65535);
    o.frustumCulled = false;
    return o;
  }
  // Four components a vertex on the GPU: Vulkan need not read three 16-bit or 8-bit
  // components natively, and ANGLE's conversion of them made SwiftShader's first frame
  // of a 100,000-face page about 0.7 s slower (docs/benchmarks.md).
  function four(xyz, fill) {
    var n = xyz ? xyz.length / 3 : fill.n, out = xyz ? new Uint16Array(4 * n) : new Uint8Array(4 * n);
    for (var i = 0; i < n; ++i) {
      if (xyz) { out[4 * i] = xyz[3 * i]; out[4 * i + 1] = xyz[3 * i + 1]; out[4 * i + 2] = xyz[3 * i + 2]; } else {
        out[4 * i] = fill.rgb[0]; out[4 * i + 1] = fill.rgb[1]; out[4 * i + 2] = fill.rgb[2]; out[4 * i + 3] = 255;
      }
    }
    return out;
  }
  var views = scene.models.map(function (m) {
    var s3 = new THREE.Scene();
    var positions = u16(m.mesh.positions), positions4 = four(positions);
    var colours = four(null, { n: positions.length / 3, rgb: base8 });
    var shaded = new THREE.MeshLambertMaterial({
      vertexColors: THREE.VertexColors, side: THREE.DoubleSide,
      polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1
    });
    // One mesh per chunk of faces, each with its own 16-bit indices.
    var first = 0, triangles = 0;
    m.mesh.chunks.forEach(function (c) {
      var g = new THREE.BufferGeometry();
      // Normals from the three-component view (what computeVertexNormals reads), then
      // the four-component positions drawn.
      g.setAttribute('position', new THREE.BufferAttribute(positions.subarray(3 * first, 3 * (first + c.vertices)), 3, true));
      g.setIndex(new THREE.BufferAttribute(c.index_bytes === 4 ? u32(c.indices) : u16(c.indices), 1));
      g.computeVertexNormals();
      g.setAttribute('position', new THREE.BufferAttribute(positions4.subarray(4 * first, 4 * (first + c.vertices)), 4, true));
      g.setAttribute('color', new THREE.BufferAttribute(colours.subarray(4 * first, 4 * (first + c.vertices)), 4, true));
      s3.add(onGrid(new THREE.Mesh(g, shaded)));
      triangles += g.index.count / 3;
      first += c.vertices;
    });

    var linePositions = u16(m.lines.positions), edgePoints = u32(m.lines.edge_points);
    var segments = 0;
    for (var e = 0; e + 1 < edgePoints.length; ++e) segments += Math.max(0, edgePoints[e + 1] - edgePoints[e] - 1);
    var lineIndex = new Uint32Array(2 * segments), k = 0;
    for (e = 0; e + 1 < edgePoints.length; ++e)
      for (var p = edgePoints[e]; p + 1 < edgePoints[e + 1]; ++p) { lineIndex[k++] = p; lineIndex[k++] = p + 1; }
    var lg = new THREE.BufferGeometry();
    lg.setAttribute('position', new THREE.BufferAttribute(four(linePositions), 4, true));
    lg.setIndex(new THREE.BufferAttribute(lineIndex, 1));
    s3.add(onGrid(new THREE.LineSegments(lg, new THREE.LineBasicMaterial({ color: 0x1e1e1e }))));

    s3.add(new THREE.AmbientLight(0xffffff, 0.5));
    var light = new THREE.DirectionalLight(0xffffff, 0.6);
    s3.add(light);
    return {
      model: m, scene: s3, light: light, colours: colours, triangles: triangles,
      faceVertices: u32(m.mesh.face_vertices), lineMaterials: [],
      segments: {}, dots: [], dotColours: [], anchors: [], anchorColours: []
    };
  });

  // ---- problems: faces tinted, edges and gap outlines thick, vertices and anchors as dots
  scene.problems.forEach(function (p) {
    var c = colourOf(p.type);
    p.marks.forEach(function (mark) {
      var v = views[mark.model];
      // A pinched face is the context of its two close edges: a light tint, so the
      // edges and the smaller problems on it stay visible.
      var tint = base.clone().lerp(c, p.type === 'pinched_face' ? 0.3 : 0.85);
      var r = Math.round(255 * tint.r), g = Math.round(255 * tint.g), b = Math.round(255 * tint.b);
      mark.faces.forEach(function (f) {
        for (var i = v.faceVertices[f]; i < v.faceVertices[f + 1]; ++i) {
          v.colours[4 * i] = r; v.colours[4 * i + 1] = g; v.colours[4 * i + 2] = b;
        }
      });
      if (mark.lines.length) (v.segments[p.type] = v.segments[p.type] || []).push.apply(v.segments[p.type], mark.lines);
      for (var i = 0; i + 2 < mark.points.length; i += 3) {
        v.dots.push(mark.points[i], mark.points[i + 1], mark.points[i + 2]);
        v.dotColours.push(c.r, c.g, c.b);
      }
      v.anchors.push(p.anchor[0], p.anchor[1], p.anchor[2]);
      v.anchorColours.push(c.r, c.g, c.b);
    });
  });
  function points(positions, colours, pixels) {
    var g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
    g.setAttribute('color', new THREE.Float32BufferAttribute(colours, 3));
    var m = new THREE.PointsMaterial({
      size: pixels, sizeAttenuation: false, map: dot, vertexColors: THREE.VertexColors,
      alphaTest: 0.5, depthTest: false, depthWrite: false
    });
    var o = new THREE.Points(g, m);
    o.renderOrder = 20;
    return o;
  }
  views.forEach(function (v) {
    // Sorted by type so the drawing order, like everything else, depends only on the data.
    Object.keys(v.segments).sort().forEach(function (type) {
      var g = new THREE.LineSegmentsGeometry();
      g.setPositions(v.segments[type]);
      var m = new THREE.LineMaterial({ color: colourOf(type).getHex(), linewidth: 4, depthTest: false });
      var o = new THREE.LineSegments2(g, m);
      o.renderOrder = 10;
      v.scene.add(o);
      v.lineMaterials.push(m);
    });
    // Problems behind the model stay visible: overlays ignore depth.
    if (v.dots.length) v.scene.add(points(v.dots, v.dotColours, 8));
    if (v.anchors.length) v.scene.add(points(v.anchors, v.anchorColours, 15));
  });

  timing.built = performance.now();  // JSON parsed, arrays decoded, meshes and overlays built

  // ---- page --------------------------------------------------------------------------
  var canvas = document.getElementById('canvas');
  var holder = document.getElementById('views');
  var labels = views.map(function (v) {
    var m = v.model;
    var l = el('div', 'label', m.name + ': ' + m.faces + ' faces, ' + m.edges + ' edges');
    holder.appendChild(l);
    return l;
  });
  var dividers = views.slice(1).map(function () { var d = el('div', 'divider'); holder.appendChild(d); return d; });

  var counts = {}, repaired = {};
  scene.problems.forEach(function (p) {
    counts[p.type] = (counts[p.type] || 0) + 1;
    if (p.resolved) repaired[p.type] = (repaired[p.type] || 0) + 1;
  });
  function legend(parent) {
    Object.keys(counts).sort().forEach(function (type) {
      var row = el('div');
      var s = el('span', 'swatch');
      s.style.background = scene.colors[type] || '#808080';
      row.appendChild(s);
      row.appendChild(document.createTextNode(type + ' \u00d7 ' + counts[type] +
        (views.length > 1 ? ', ' + (repaired[type] || 0) + ' gone after' : '')));
      parent.appendChild(row);
    });
  }
  if (still) {
    var lg = el('div');
    lg.id = 'legend';
    lg.appendChild(el('div', null, scene.title + ' \u2014 tolerance ' + num(scene.tolerance) + ' ' + scene.units));
    legend(lg);
    if (!scene.problems.length) lg.appendChild(el('div', null, 'no problems'));
    holder.appendChild(lg);
  }

  var side = document.getElementById('side');
  side.appendChild(el('h1', null, scene.title));
  side.appendChild(el('div', 'summary', 'tolerance t = ' + num(scene.tolerance) + ' ' + scene.units + '; ' +
    scene.problems.length + ' problem(s)' + (views.length > 1 ? ' (marked before; those not repaired also after)' : '')));
  legend(side);
  side.appendChild(el('div', 'hint', 'Drag: rotate, wheel: zoom, right drag: pan. Click a problem to frame it.'));
  views.forEach(function (v) {
    v.model.untessellated.forEach(function (u) {
      side.appendChild(el('div', 'warning', v.model.name + ': ' + u.face + ' not shaded (' + u.reason + ')'));
    });
  });

  function sizeText(p) {
    if (p.measure === null) return 'size not measured';
    var t = scene.tolerance, area = /area/.test(p.measure_name || '');
    var ratio = t > 0 ? (area ? p.measure / (t * t) : p.measure / t) : NaN;
    return (p.measure_name || 'measure') + ' ' + num(p.measure) + ' ' + scene.units + (area ? '\u00b2' : '') +
      ' = ' + num(ratio) + (area ? ' t\u00b2' : ' t');
  }
  var list = el('ol');
  list.id = 'problems';
  side.appendChild(list);
  var items = scene.problems.map(function (p, n) {
    var li = el('li');
    li.setAttribute('data-index', String(n));
    li.setAttribute('data-type', p.type);
    var s = el('span', 'swatch');
    s.style.background = scene.colors[p.type] || '#808080';
    li.appendChild(s);
    li.appendChild(el('b', null, (n + 1) + '. ' + p.type));
    if (p.subcase) li.appendChild(document.createTextNode(' (' + p.subcase + ')'));
    var missing = [];
    p.marks.forEach(function (m) { if (m.missing.length) missing.push(m.missing.join(' ') + ' not in ' + scene.models[m.model].name); });
    li.appendChild(el('div', 'where', 'at ' + p.elements.join(' ') + (missing.length ? ' (' + missing.join('; ') + ')' : '')));
    li.appendChild(el('div', 'size', sizeText(p)));
    if (p.action) {
      var done = p.action + (p.operators.length ? ': ' + p.operators.join(', ') : '') + (p.reason ? ' \u2014 ' + p.reason : '') +
        (p.deviation !== null && p.action === 'repaired' ? '; deviation ' + num(p.deviation) + ' ' + scene.units : '');
      li.appendChild(el('div', 'done' + (p.resolved ? '' : ' not-repaired'), done));
    }
    li.addEventListener('click', function () { frame(n); });
    list.appendChild(li);
    return li;
  });

  // ---- camera, controls, drawing -------------------------------------------------------
  timing.listed = performance.now();
  // Antialiasing only for pages a software rasteriser draws quickly: on a machine
  // without a GPU (SwiftShader) multisampling 266k triangles (a 10,000-face model) took
  // 42 s for the first frame, 26 s without it (docs/benchmarks.md).
  var triangles = views.reduce(function (n, v) { return n + v.triangles; }, 0);
  var renderer = new THREE.WebGLRenderer({
    canvas: canvas, antialias: triangles <= 100000, preserveDrawingBuffer: true
  });
  timing.webgl = performance.now();  // a WebGL context (with software rendering, starting it dominates small pages)
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(0xffffff, 1);
  var camera = new THREE.PerspectiveCamera(30, 1, size * 1e-3, size * 10);
  camera.up.set(0, 0, 1);
  var controls = new THREE.OrbitControls(camera, canvas);
  controls.screenSpacePanning = true;

  function viewportWidth() { return Math.max(1, Math.floor(canvas.clientWidth / views.length)); }
  function layout() {
    var w = canvas.clientWidth, h = Math.max(1, canvas.clientHeight);
    var s = renderer.getSize(new THREE.Vector2());
    if (s.x !== w || s.y !== h) renderer.setSize(w, h, false);
    camera.aspect = viewportWidth() / h;
    labels.forEach(function (l, i) { l.style.left = (i * viewportWidth() + 8) + 'px'; });
    dividers.forEach(function (d, i) { d.style.left = ((i + 1) * viewportWidth()) + 'px'; });
  }
  // Distance at which a sphere of `radius` fills the narrower field of view.
  function fitDistance(radius) {
    var v = camera.fov * Math.PI / 180, hz = 2 * Math.atan(Math.tan(v / 2) * camera.aspect);
    return radius / Math.sin(Math.min(v, hz) / 2);
  }
  function cameraText() {
    return camera.position.toArray().concat(controls.target.toArray()).map(function (x) { return x.toPrecision(6); }).join(',');
  }
  function screenPositions() {
    var rect = canvas.getBoundingClientRect(), w = viewportWidth();
    var v = new THREE.Vector3();
    items.forEach(function (li, n) {
      var p = scene.problems[n], parts = [];
      p.marks.forEach(function (mark) {
        v.fromArray(p.anchor).project(camera);
        if (v.z < -1 || v.z > 1) return;
        var x = rect.left + window.scrollX + mark.model * w + (v.x + 1) / 2 * w;
        var y = rect.top + window.scrollY + (1 - v.y) / 2 * rect.height;
        parts.push(mark.model + ':' + x.toFixed(1) + ',' + y.toFixed(1));
      });
      li.setAttribute('data-screen', parts.join(' '));
    });
  }
  function render() {
    layout();
    var d = camera.position.distanceTo(controls.target);
    camera.near = Math.max(d * 0.01, size * 1e-7);
    camera.far = d + 4 * size;
    camera.updateProjectionMatrix();
    var w = viewportWidth(), h = Math.max(1, canvas.clientHeight);
    renderer.setScissorTest(true);
    views.forEach(function (v, i) {
      renderer.setViewport(i * w, 0, w, h);
      renderer.setScissor(i * w, 0, w, h);
      v.lineMaterials.forEach(function (m) { m.resolution.set(w, h); });
      v.light.position.copy(camera.position).sub(controls.target).normalize();
      v.light.target.position.set(0, 0, 0);
      renderer.render(v.scene, camera);
    });
    renderer.setScissorTest(false);
    screenPositions();
    document.body.setAttribute('data-camera', cameraText());
  }

  function frame(n) {
    var p = scene.problems[n];
    var anchor = new THREE.Vector3().fromArray(p.anchor);
    var radius = Math.max(1.5 * p.radius, 0.04 * size, 10 * scene.tolerance);
    var dir = camera.position.clone().sub(controls.target).normalize();
    controls.target.copy(anchor);
    camera.position.copy(anchor).addScaledVector(dir, fitDistance(radius));
    items.forEach(function (li, i) { li.classList.toggle('selected', i === n); });
    controls.update();  // fires 'change', which renders
    render();
  }

  layout();
  controls.target.set(0, 0, 0);
  camera.position.copy(new THREE.Vector3(1.0, -1.6, 1.1).normalize().multiplyScalar(fitDistance(0.5 * size * 1.05)));
  controls.update();
  controls.addEventListener('change', render);
  window.addEventListener('resize', render);
  render();
  // Wait for the GPU, so that data-render-ms is the time until the picture exists.
  var gl = renderer.getContext(), pixel = new Uint8Array(4);
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
  timing.rendered = performance.now();
  document.body.setAttribute('data-render-ms', timing.rendered.toFixed(0));
  document.body.setAttribute('data-timing', Object.keys(timing).map(function (k) { return k + ':' + timing[k].toFixed(0); }).join(' '));
  document.body.setAttribute('data-camera-initial', cameraText());
  var click = params.get('click');
  if (click !== null && items[Number(click)]) items[Number(click)].click();
  document.body.setAttribute('data-ready', '1');
})();
