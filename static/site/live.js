/* Sentinel live pages — our own small client (no CDN, no htmx ws extension).
 *
 * The server pushes re-rendered `[data-live]` regions of this page as out-of-band swaps over
 * the websocket `/r/<token>/live` (apps/kit/consumers.py) when the run's log grows and when the
 * clock changes what they show; when the socket cannot connect, the same URL is polled over
 * HTTP every `data-poll-ms` (2 s), with `due` (when the page next changes with the clock, as
 * the server said: data-due, then each update's next_change). The client keeps what the user is
 * doing: window and region scroll positions, focus, checked rows, chosen options and the menus
 * and sections (`<details>`) it opened or closed, matched by place and label; a region
 * holding a field being typed in, or typed text not sent yet, is swapped only once the user
 * leaves it. A page's own answer to a boosted form or link keeps the menus the person opened or
 * closed while it was on its way (after a push had already shown the change, say) when it
 * redraws the same page. Config: <div id="sentinel-live" data-socket data-seq data-due data-poll-ms>.
 */
(function () {
  "use strict";
  var config = null, configNode = null, socket = null, subscribed = null;
  var seq = 0, due = null, pollTimer = null, retryMs = 1000, pending = {};

  function pageUrl() { return location.pathname + location.search; }
  function hasSocket() { return typeof window.WebSocket === "function"; }

  function isText(field) {
    return field.tagName === "TEXTAREA" || field.isContentEditable || (field.tagName === "INPUT" &&
      !/^(checkbox|radio|button|submit|reset|hidden|image|file)$/i.test(field.type));
  }
  function busy(region) {
    var active = document.activeElement;
    if (active && region.contains(active) && (isText(active) || active.tagName === "SELECT")) return true;
    return Array.prototype.some.call(region.querySelectorAll("input, textarea"), function (f) {
      return isText(f) && f.value !== f.defaultValue;
    });
  }

  function summaryOf(details) {
    var summary = details.querySelector("summary");
    return summary ? summary.textContent.trim() + "|" + (summary.getAttribute("aria-label") || "") : "";
  }

  function menuStates(root) {
    return Array.prototype.map.call(root.querySelectorAll("details"), function (d) {
      return [summaryOf(d), d.open];
    });
  }
  function restoreMenus(root, menus) {  // the same menu, by place and label
    root.querySelectorAll("details").forEach(function (d, i) {
      if (menus[i] && menus[i][0] === summaryOf(d) && menus[i][1] !== null) d.open = menus[i][1];
    });
  }

  // A boosted request answers with the whole page, drawn as the server left it. The menus the
  // person toggled while it travelled (a push may have shown the change already) are theirs:
  // kept when the answer redraws the same page, as a push keeps them. A menu untouched meanwhile
  // takes the answer's state, so one whose item was chosen closes.
  var asked = null, toggled = null;  // [page URL, menu states] as the request left; what changed
  document.addEventListener("htmx:beforeRequest", function () {
    asked = [pageUrl(), menuStates(document)];
  });
  document.addEventListener("htmx:beforeSwap", function () {
    toggled = asked && menuStates(document).map(function (menu, i) {
      var was = asked[1][i];
      return was && was[0] === menu[0] && was[1] !== menu[1] ? menu : [menu[0], null];
    });
  });
  document.addEventListener("htmx:afterSwap", function (event) {
    var xhr = event.detail && event.detail.xhr, was = asked, menus = toggled;
    asked = toggled = null;
    if (!was || !menus || !xhr || !xhr.responseURL) return;
    var answered = new URL(xhr.responseURL);
    if (answered.pathname + answered.search === was[0]) restoreMenus(document, menus);
  });

  function csrfToken() {  // the page's own token (pushed forms come with blank ones)
    try { return JSON.parse(document.body.getAttribute("hx-headers") || "{}")["X-CSRFToken"] || ""; }
    catch (e) { return ""; }
  }

  function swap(fresh) {
    var old = document.getElementById(fresh.id);
    if (!old) return;
    if (busy(old)) { pending[fresh.id] = fresh; return; }
    delete pending[fresh.id];
    var x = window.scrollX, y = window.scrollY, scrolled = [], chosen = [];
    var focused = old.contains(document.activeElement) ? document.activeElement.id : "";
    [old].concat(Array.prototype.slice.call(old.querySelectorAll("[id]"))).forEach(function (el) {
      if (el.scrollTop || el.scrollLeft) scrolled.push([el.id, el.scrollTop, el.scrollLeft]);
    });
    var menus = menuStates(old);
    old.querySelectorAll("input[id], select[id]").forEach(function (f) {
      if ((f.type === "checkbox" || f.type === "radio") && f.checked !== f.defaultChecked) chosen.push([f.id, "checked", f.checked]);
      if (f.tagName === "SELECT" && f.selectedOptions.length && !f.selectedOptions[0].defaultSelected) chosen.push([f.id, "value", f.value]);
    });
    fresh.removeAttribute("hx-swap-oob");
    var token = csrfToken();
    fresh.querySelectorAll("input[name=csrfmiddlewaretoken]").forEach(function (f) { if (!f.value) f.value = token; });
    old.replaceWith(fresh);
    chosen.forEach(function (c) { var f = document.getElementById(c[0]); if (f) f[c[1]] = c[2]; });
    restoreMenus(fresh, menus);
    scrolled.forEach(function (s) { var el = document.getElementById(s[0]); if (el) { el.scrollTop = s[1]; el.scrollLeft = s[2]; } });
    if (window.htmx) window.htmx.process(fresh);
    if (focused && document.getElementById(focused)) document.getElementById(focused).focus({ preventScroll: true });
    window.scrollTo(x, y);
  }

  function apply(message) {
    // A clock-driven update keeps the log position: equal is new enough (the server sends only
    // regions that read differently, in order).
    if (!message || message.type !== "regions" || message.seq < seq || message.url !== pageUrl()) return;
    seq = message.seq;
    due = typeof message.next_change === "number" ? message.next_change : null;
    // Kept on the config node too, so whoever reads the page (a fast-forward agent waiting for
    // it to catch up with a skip) sees which log position and clock window it shows.
    if (configNode) { configNode.dataset.seq = String(seq); configNode.dataset.due = due === null ? "" : String(due); }
    var holder = document.createElement("template");
    holder.innerHTML = message.html;
    Array.prototype.slice.call(holder.content.children).forEach(function (el) { if (el.id) swap(el); });
    document.dispatchEvent(new CustomEvent("sentinel:live", { detail: { seq: seq } }));
  }
  document.addEventListener("focusout", function () {
    setTimeout(function () { Object.keys(pending).forEach(function (id) { swap(pending[id]); }); }, 0);
  });

  function poll() {
    if (!config) return;
    fetch(config.socket + "?url=" + encodeURIComponent(pageUrl()) + "&seq=" + seq + "&due=" + (due === null ? "" : due),
          { credentials: "same-origin", headers: { Accept: "application/json" } })
      .then(function (r) { return r.status === 200 ? r.json() : null; })
      .then(apply, function () {});
  }
  function startPolling() { if (!pollTimer && config) pollTimer = setInterval(poll, config.pollMs); }
  function stopPolling() { clearInterval(pollTimer); pollTimer = null; }

  function subscribe() {
    if (socket && socket.readyState === 1 && subscribed !== pageUrl()) {
      subscribed = pageUrl();
      socket.send(JSON.stringify({ url: subscribed, seq: seq, due: due }));
    }
  }
  function connect() {
    if (!config) return;
    if (!hasSocket()) { startPolling(); return; }
    var path = config.socket, ws;
    try { ws = new WebSocket((location.protocol === "https:" ? "wss://" : "ws://") + location.host + path); }
    catch (e) { startPolling(); return; }
    socket = ws;
    ws.onopen = function () { retryMs = 1000; stopPolling(); subscribed = null; subscribe(); };
    ws.onmessage = function (e) { try { apply(JSON.parse(e.data)); } catch (err) { /* ignore a bad frame */ } };
    ws.onclose = function () {
      if (socket !== ws) return;  // replaced on purpose
      socket = null; subscribed = null;
      startPolling();  // cover the gap; try the socket again with back-off
      setTimeout(function () { if (!socket && config && config.socket === path) connect(); }, retryMs);
      retryMs = Math.min(retryMs * 2, 30000);
    };
  }

  function refresh() {
    var node = document.getElementById("sentinel-live");
    if (!node) { config = null; stopPolling(); if (socket) { var s = socket; socket = null; s.close(); } return; }
    if (node !== configNode) {  // a new page (load or boosted navigation): its own log position
      configNode = node; pending = {}; subscribed = null;
      seq = parseInt(node.dataset.seq || "0", 10);
      due = node.dataset.due ? parseFloat(node.dataset.due) : null;
      var socketPath = node.dataset.socket, changed = !config || config.socket !== socketPath;
      config = { socket: socketPath, pollMs: parseInt(node.dataset.pollMs || "2000", 10) };
      if (changed) {
        if (socket) { var old = socket; socket = null; old.close(); }
        stopPolling(); connect();
      }
    }
    subscribe();  // a no-op unless the URL changed or this is a new page
  }

  ["htmx:afterSettle", "htmx:historyRestore", "htmx:pushedIntoHistory", "htmx:replacedInHistory"]
    .forEach(function (name) { document.addEventListener(name, refresh); });
  window.addEventListener("popstate", function () { setTimeout(refresh, 0); });
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", refresh);
  else refresh();
})();
