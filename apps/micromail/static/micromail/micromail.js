/* MicroMail in the browser: what a mail client does beyond links and forms, all of it optional
 * (every page works without JavaScript). Loaded once in the page head; boosted navigations
 * (hx-boost) keep it running, so everything here is delegated from `document` and set up again
 * after each swap.
 *
 * 1. The message list keeps its scroll position. Opening a message, a preview or any screen of
 *    the same list is a new page (its own URL), so the list's scrollTop is kept in
 *    sessionStorage under the list's URL (the page's URL without `email` and `preview`) and put
 *    back as soon as the new page is in. Live pushes keep it too (static/site/live.js keeps the
 *    scroll of every region it swaps).
 * 2. The attachment preview is a modal dialog: focus goes to it, Escape closes it.
 * 3. Compose saves a draft on its own (save_draft, the same action as the "Save draft" button)
 *    after a pause in typing, on leaving a field, and before leaving the page, into one draft
 *    (its id comes back and rides along in `draft_id`). Discard asks first, in a <dialog>.
 */
(function () {
  "use strict";
  var SCROLL_KEY = "micromail:list-scroll:";
  var PAUSE_MS = 3000;  // typing pause after which the draft is saved
  var AUTOSAVE_HEADER = "X-MicroMail-Autosave";  // views.AUTOSAVE_HEADER

  // --- 1. the message list's scroll position -----------------------------------------------------

  function list() { return document.getElementById("message-list"); }
  function listKey() {
    var params = new URLSearchParams(location.search);
    params.delete("email");
    params.delete("preview");
    return SCROLL_KEY + location.pathname + "?" + params.toString();
  }
  function rememberScroll() {
    var node = list();
    if (node) sessionStorage.setItem(listKey(), String(node.scrollTop));
  }
  function restoreScroll() {
    var node = list();
    if (!node) return;
    var saved = sessionStorage.getItem(listKey());
    if (saved !== null) node.scrollTop = parseFloat(saved);
    // A message opened from its URL (no position kept) is brought into view.
    var opened = node.querySelector(".message.opened");
    if (opened && saved === null) opened.scrollIntoView({ block: "center" });
  }
  document.addEventListener("scroll", function (event) {
    if (event.target === list()) rememberScroll();
  }, true);

  // --- 2. the attachment preview ---------------------------------------------------------------

  function setUpPreview() {
    var close = document.getElementById("preview-close");
    if (close) close.focus({ preventScroll: true });
  }
  document.addEventListener("keydown", function (event) {
    if (event.key !== "Escape") return;
    var close = document.getElementById("preview-close");
    if (close) { event.preventDefault(); close.click(); }
  });

  // --- 3. compose: auto-saved drafts, the discard confirmation, attached files ------------------

  var compose = null;  // { form, saved, timer, saving, again, resubmit, sending }

  function snapshot(form) {
    var data = new FormData(form);
    data.delete("csrfmiddlewaretoken");
    data.delete("draft_id");
    data.delete("intent");
    return new URLSearchParams(data).toString();
  }
  function hasContent(form) {
    var typed = ["to", "cc", "bcc", "subject", "body"].some(function (name) {
      return form.elements[name] && form.elements[name].value.trim() !== "";
    });
    return typed || form.querySelector("input[name=attachments]:checked") !== null;
  }
  function csrf(form) {
    var field = form.querySelector("input[name=csrfmiddlewaretoken]");
    return field ? field.value : "";
  }
  function say(text) {
    var status = document.getElementById("draft-status");
    if (status) status.textContent = text;
  }

  function saveDraft(options, pending) {
    // `pending`: the compose state a save in flight was asked to save again. When the user left
    // meanwhile, its form is no longer on the page, but what was typed is still in it: saved.
    var state = pending || compose;
    var leaving = Boolean(options && options.leaving);
    if (!state || state.sending) return;
    if (!pending && !document.body.contains(state.form)) return;
    clearTimeout(state.timer);
    var form = state.form, now = snapshot(form);
    if (now === state.saved || !hasContent(form)) return;
    if (state.saving) { state.again = leaving ? "leaving" : state.again || "later"; return; }
    state.saving = true;
    say("Saving…");
    var data = new FormData(form);
    data.set("intent", "save_draft");
    var headers = { "X-CSRFToken": csrf(form), Accept: "application/json" };
    headers[AUTOSAVE_HEADER] = "1";
    fetch(form.action, { method: "POST", body: data, headers: headers, credentials: "same-origin",
                         keepalive: leaving })
      .then(function (response) { return response.json(); })
      .then(function (answer) {
        if (answer && answer.draft_id) {
          form.elements.draft_id.value = answer.draft_id;
          state.saved = now;
          say("Draft saved");
        } else {
          say(answer && answer.error ? "Not saved: " + answer.error : "Not saved");
        }
      }, function () { say("Not saved: no connection"); })
      .then(function () {
        state.saving = false;
        if (state.resubmit) {  // Send or Discard waited for this save: go on with its draft id
          var button = state.resubmit; state.resubmit = null;
          form.requestSubmit(button);
        } else if (state.again) {
          var again = state.again; state.again = false;
          saveDraft({ leaving: again === "leaving" }, state);  // with the draft id just given
        }
      });
  }

  function renderAttached(form) {
    var shelf = document.getElementById("attached-files");
    if (!shelf) return;
    shelf.textContent = "";
    form.querySelectorAll("input[name=attachments]:checked").forEach(function (box) {
      var chip = document.createElement("li");
      chip.dataset.attachment = box.value;
      var kind = box.closest("label").querySelector(".file-type");
      if (kind) chip.appendChild(kind.cloneNode(true));
      chip.appendChild(document.createTextNode(" " + box.dataset.name + " "));
      var size = document.createElement("span");
      size.className = "size";
      size.textContent = box.dataset.size;
      chip.appendChild(size);
      var remove = document.createElement("button");
      remove.type = "button";
      remove.className = "icon";
      remove.setAttribute("aria-label", "Remove " + box.dataset.name);
      remove.innerHTML = '<svg class="lucide" width="14" height="14" aria-hidden="true"><use href="#icon-x"></use></svg>';
      remove.addEventListener("click", function () {
        box.checked = false;
        box.dispatchEvent(new Event("change", { bubbles: true }));
      });
      chip.appendChild(remove);
      shelf.appendChild(chip);
    });
  }

  function setUpCompose() {
    var form = document.getElementById("compose-form");
    if (!form || (compose && compose.form === form)) return;
    compose = { form: form, saved: snapshot(form), timer: null, saving: false, again: false,
                resubmit: null, sending: false };
    var state = compose;
    renderAttached(form);
    form.addEventListener("input", function () {
      clearTimeout(state.timer);
      state.timer = setTimeout(saveDraft, PAUSE_MS);
    });
    form.addEventListener("change", function (event) {
      if (event.target.name === "attachments") { renderAttached(form); saveDraft(); }
    });
    // Leaving a field saves, a moment later: a click on Send or Discard (which blurs the field
    // first) cancels that save and does its own thing with the form.
    form.addEventListener("focusout", function () {
      clearTimeout(state.timer);
      state.timer = setTimeout(saveDraft, 300);
    });
    var dialog = document.getElementById("discard-dialog");
    var discard = document.getElementById("compose-discard");
    if (dialog && discard && typeof dialog.showModal === "function") {
      discard.addEventListener("click", function (event) {
        event.preventDefault();
        clearTimeout(state.timer);
        dialog.showModal();
        document.getElementById("discard-cancel").focus();
      });
      document.getElementById("discard-cancel").addEventListener("click", function () {
        dialog.close();
        discard.focus();
      });
    }
  }

  // Window capture runs before htmx's own submit handling on the form.
  window.addEventListener("submit", function (event) {
    var state = compose;
    if (!state || event.target !== state.form) return;
    clearTimeout(state.timer);
    if (state.saving) {  // wait for the draft's id, so Send or Discard replaces that draft
      event.preventDefault();
      event.stopPropagation();
      state.resubmit = event.submitter || null;
      return;
    }
    state.sending = true;
  }, true);

  // Before going anywhere else, whatever was typed is saved.
  document.addEventListener("htmx:beforeRequest", function (event) {
    rememberScroll();
    var state = compose;
    if (state && !state.sending && event.detail.elt !== state.form &&
        !state.form.contains(event.detail.elt)) saveDraft({ leaving: true });
  });
  window.addEventListener("pagehide", function () {
    rememberScroll();
    if (compose && !compose.sending) saveDraft({ leaving: true });
  });

  function setUp() {
    restoreScroll();
    setUpPreview();
    setUpCompose();
  }
  document.addEventListener("htmx:afterSwap", setUp);
  document.addEventListener("htmx:historyRestore", setUp);
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", setUp);
  else setUp();
})();
