// Flip, zoom and synchronised scrolling, per .compare block (core/eval/report/images.html).
function show(img, ref) {
  img.src = ref ? img.dataset.ref : img.dataset.run;
  img.dataset.showing = ref ? 'ref' : 'run';
  img.closest('figure').querySelector('.which').textContent = ref ? 'reference' : 'run ' + img.dataset.id;
}
document.querySelectorAll('.compare').forEach(function (box) {
  var imgs = box.querySelectorAll('img.flip'), panes = box.querySelectorAll('.pane'), all = false, busy = false;
  imgs.forEach(function (img) {
    img.addEventListener('click', function () { show(img, img.dataset.showing !== 'ref'); });
  });
  box.querySelector('.flip-all').addEventListener('click', function (e) {
    all = !all;
    imgs.forEach(function (img) { show(img, all); });
    e.target.textContent = all ? 'show all runs' : 'show all references';
  });
  box.querySelector('.zoom').addEventListener('change', function (e) {
    var z = e.target.value;
    box.querySelectorAll('.pane img, .pane video').forEach(function (media) {
      var width = media.naturalWidth || media.videoWidth;
      media.style.width = z === 'fit' ? '100%' : (width * z) + 'px';
    });
  });
  panes.forEach(function (p) {
    p.addEventListener('scroll', function () {
      if (busy) return;
      busy = true;
      panes.forEach(function (q) { if (q !== p) { q.scrollLeft = p.scrollLeft; q.scrollTop = p.scrollTop; } });
      requestAnimationFrame(function () { busy = false; });
    });
  });
});
