// The watch page's player controls, client-side only (as in the original): play/pause swaps
// the animated poster for its still, the progress bar follows, theater mode widens the player.
(function () {
  function wire(root) {
    root.querySelectorAll("[data-player]:not([data-wired])").forEach(function (player) {
      player.setAttribute("data-wired", "");
      var play = player.querySelector("[data-play]");
      var mute = player.querySelector("[data-mute]");
      var theater = player.querySelector("[data-theater]");
      var elapsed = player.querySelector("[data-elapsed]");
      var seconds = 0;
      var timer = setInterval(function () {
        if (!document.body.contains(player)) { clearInterval(timer); return; }
        if (player.classList.contains("paused")) return;
        seconds += 1;
        elapsed.textContent = Math.floor(seconds / 60) + ":" + String(seconds % 60).padStart(2, "0");
      }, 1000);
      play.addEventListener("click", function () {
        var paused = player.classList.toggle("paused");
        play.setAttribute("aria-label", paused ? "Play" : "Pause");
        play.setAttribute("aria-pressed", paused ? "false" : "true");
      });
      mute.addEventListener("click", function () {
        var muted = mute.getAttribute("aria-label") === "Unmute";
        mute.setAttribute("aria-label", muted ? "Mute" : "Unmute");
      });
      theater.addEventListener("click", function () {
        document.body.classList.toggle("theater");
      });
    });
  }
  document.addEventListener("DOMContentLoaded", function () { wire(document); });
  document.addEventListener("htmx:afterSettle", function (e) { wire(e.target); });
  // A dropdown closes when the user clicks elsewhere.
  document.addEventListener("click", function (e) {
    document.querySelectorAll("details[data-dropdown][open]").forEach(function (d) {
      if (!d.contains(e.target)) d.removeAttribute("open");
    });
  });
})();
