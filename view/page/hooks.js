// Runs before every other script of the page: errors (exceptions, rejected promises,
// console.error) are written into the DOM, where a headless browser's --dump-dom can
// read them back (body[data-errors] counts them, #errors lists them).
(function () {
  'use strict';
  var errors = [];
  function show() {
    if (!document.body) return;
    document.body.setAttribute('data-errors', String(errors.length));
    var pre = document.getElementById('errors');
    if (pre) {
      pre.textContent = errors.join('\n');
      pre.hidden = false;
    }
  }
  function note(message) {
    errors.push(String(message));
    if (document.body) show();
    else document.addEventListener('DOMContentLoaded', show);
  }
  window.kintsugiNoteError = note;
  window.addEventListener('error', function (e) {
    note('error: ' + (e.message || e) + (e.lineno ? ' (line ' + e.lineno + ')' : ''));
  });
  window.addEventListener('unhandledrejection', function (e) { note('unhandled rejection: ' + e.reason); });
  var original = console.error;
  console.error = function () {
    note('console.error: ' + Array.prototype.join.call(arguments, ' '));
    return original.apply(console, arguments);
  };
})();
