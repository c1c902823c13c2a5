/* Sentinel shell: a rejected form stays on screen under hx-boost (htmx 2, bundled by django-htmx).
 *
 * Environments answer a rejected form (a bad address, an unknown message, a conflict) with the
 * page re-rendered around the error and an HTTP 400/404/409/422: what a browser shows without
 * JavaScript. htmx 2 swaps only 2xx/3xx answers by default, so with the shell's hx-boost the page
 * would not change at all and whoever submitted would believe it went through. Here those answers
 * are swapped like a success, when they are HTML; any other error keeps htmx's default (no swap).
 *
 * The URL after a rejected POST stays the URL of the page that held the form, and no history
 * entry is added: nothing was navigated to, the same form is still on screen with the reason it
 * was refused. htmx would otherwise push the POST URL, whose GET is another page (MicroMail's
 * `compose` without its `?mode=reply&email=…` is an empty "New message"), so Back would show an
 * emptied copy of the form and reload would drop the reply context. A rejected GET (a boosted link
 * to a page that is not there) is a navigation: htmx pushes its URL as for any link.
 */
(function () {
  "use strict";
  var htmx = window.htmx;
  if (!htmx) return;

  var REJECTED = "^(400|404|409|422)$";

  // htmx 2's documented switch: the first responseHandling entry whose code matches decides.
  htmx.config.responseHandling.unshift({ code: REJECTED, swap: true, error: false });

  function isRejected(xhr) { return new RegExp(REJECTED).test(String(xhr.status)); }
  function isHtml(xhr) { return /^text\/html\b/i.test(xhr.getResponseHeader("Content-Type") || ""); }

  // A plain-text or JSON error is not a page: leave it unswapped, as htmx does by default.
  document.addEventListener("htmx:beforeSwap", function (event) {
    var detail = event.detail;
    if (isRejected(detail.xhr) && !isHtml(detail.xhr)) {
      detail.shouldSwap = false;
      detail.isError = true;
    }
  });

  // Documented for htmx 2: "can be used to modify the path or type used to update the history".
  document.addEventListener("htmx:beforeHistoryUpdate", function (event) {
    var detail = event.detail;
    if (!isRejected(detail.xhr) || detail.requestConfig.verb === "get") return;
    detail.history.type = "replace";
    detail.history.path = location.pathname + location.search + location.hash;
  });
})();
