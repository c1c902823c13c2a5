// Open a chat at its newest message, as Teams does: on load and after a boosted navigation.
(function () {
  function toNewest() {
    var list = document.getElementById("messages");
    if (list && !location.hash) list.scrollTop = list.scrollHeight;
  }
  document.addEventListener("DOMContentLoaded", toNewest);
  document.addEventListener("htmx:afterSettle", toNewest);
})();
