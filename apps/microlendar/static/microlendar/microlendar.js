/* MicroLendar's small progressive enhancement (the pages work without it).
 *
 * - Drag and drop to reschedule: dropping an event on a month cell or a day column sends the
 *   very POST the details' "Reschedule" form sends (events/<id>/reschedule with date, and time
 *   in the grids, snapped to 15 minutes): one action, one logged payload shape.
 * - A click on an empty slot of a day column opens the new-event form for that day and hour.
 * - The day/week grid opens scrolled to 8 AM (or the current time), as Google Calendar does.
 * - Upstream's start pages name the view in the hash (`microlendar#week`): it becomes ?view=week.
 */
(function () {
  "use strict";
  var HOUR_PX = 48, SNAP_MIN = 15;
  var VIEWS = ["day", "week", "month", "year", "schedule", "4days"];

  var hash = location.hash.replace("#", "");
  if (VIEWS.indexOf(hash) >= 0 && !/[?&]view=/.test(location.search)) {
    location.replace(location.pathname + "?view=" + hash);
    return;
  }

  function main() { return document.getElementById("main"); }
  function pad(n) { return (n < 10 ? "0" : "") + n; }
  function csrf() {
    try { return JSON.parse(document.body.getAttribute("hx-headers") || "{}")["X-CSRFToken"] || ""; }
    catch (e) { return ""; }
  }

  function post(url, fields) {
    var form = document.createElement("form");
    form.method = "post";
    form.action = url;
    fields.csrfmiddlewaretoken = csrf();
    Object.keys(fields).forEach(function (name) {
      var input = document.createElement("input");
      input.type = "hidden"; input.name = name; input.value = fields[name];
      form.appendChild(input);
    });
    document.body.appendChild(form);
    form.submit();
  }

  function minutesAt(column, clientY, grabOffset) {
    var y = clientY - column.getBoundingClientRect().top - (grabOffset || 0);
    var minutes = Math.round((y / HOUR_PX) * 60 / SNAP_MIN) * SNAP_MIN;
    return Math.max(0, Math.min(minutes, 24 * 60 - SNAP_MIN));
  }

  var dragged = null;
  document.addEventListener("dragstart", function (event) {
    var item = event.target.closest && event.target.closest("[data-event]");
    if (!item) return;
    dragged = { id: item.getAttribute("data-event"), offset: event.clientY - item.getBoundingClientRect().top };
    event.dataTransfer.setData("text/plain", dragged.id);
    event.dataTransfer.effectAllowed = "move";
  });
  document.addEventListener("dragover", function (event) {
    if (dragged && event.target.closest && event.target.closest("[data-date]")) event.preventDefault();
  });
  document.addEventListener("drop", function (event) {
    var target = event.target.closest && event.target.closest("[data-date]");
    if (!dragged || !target || !main()) return;
    event.preventDefault();
    var fields = { date: target.getAttribute("data-date"), back: main().getAttribute("data-back") || "" };
    if (target.classList.contains("daycol")) {
      var m = minutesAt(target, event.clientY, dragged.offset);
      fields.time = pad(Math.floor(m / 60)) + ":" + pad(m % 60);
    }
    post(main().getAttribute("data-root") + "events/" + encodeURIComponent(dragged.id) + "/reschedule", fields);
    dragged = null;
  });
  document.addEventListener("dragend", function () { dragged = null; });

  document.addEventListener("click", function (event) {
    var column = event.target.classList && event.target.classList.contains("daycol") ? event.target : null;
    if (!column || !main()) return;
    var hour = Math.floor(minutesAt(column, event.clientY) / 60);
    location.href = main().getAttribute("data-root") + "events/new?date=" + column.getAttribute("data-date") +
      "&time=" + pad(hour) + ":00&back=" + encodeURIComponent(main().getAttribute("data-back") || "");
  });

  var LABEL_ROOM_PX = 12;
  function scrollGrid() {
    var grid = document.getElementById("tg-scroll");
    if (!grid || grid.dataset.scrolled) return;
    grid.dataset.scrolled = "1";
    var line = grid.querySelector(".now-line");
    var top = line ? parseInt(line.style.top, 10) - 3 * HOUR_PX : 8 * HOUR_PX;
    // A little above the hour line, so that hour's label (drawn across the line) shows whole.
    grid.scrollTop = Math.max(top - LABEL_ROOM_PX, 0);
  }
  document.addEventListener("DOMContentLoaded", scrollGrid);
  document.addEventListener("htmx:afterSettle", scrollGrid);
})();
