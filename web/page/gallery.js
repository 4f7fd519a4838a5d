// The gallery page: one <stl-tree src="examples/NAME"> per example
// (examples/index.json, written by web/build.sh).

const res = await fetch('examples/index.json');
const { examples } = await res.json();
const gallery = document.getElementById('gallery');
for (const name of examples) {
  const figure = document.createElement('figure');
  const tree = document.createElement('stl-tree');
  tree.setAttribute('src', 'examples/' + name);
  const caption = document.createElement('figcaption');
  caption.textContent = name;
  figure.append(tree, caption);
  gallery.append(figure);
}
