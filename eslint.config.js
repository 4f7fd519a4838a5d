// ESLint for the `stlc serve` page (src/serve/page) and the static
// site's own modules (web/page): ES modules in the browser. Run by .ci/run (`npm ci && npx eslint`); versions pinned in
// package.json and package-lock.json.
import js from '@eslint/js';
import globals from 'globals';

export default [
  {
    files: ['src/serve/page/**/*.js', 'web/page/**/*.js', 'tests/page/**/*.js'],
    ...js.configs.recommended,
    languageOptions: {
      ecmaVersion: 2022,
      sourceType: 'module',
      globals: { ...globals.browser },
    },
    rules: {
      ...js.configs.recommended.rules,
      'no-undef': 'error',
    },
  },
  {
    // The page's pure modules tested in Node (`node --test tests/page`).
    files: ['tests/page/**/*.js'],
    languageOptions: { globals: { ...globals.node } },
  },
  {
    // The WebAssembly engine's worker.
    files: ['web/page/engine/worker.js'],
    languageOptions: { globals: { ...globals.worker } },
  },
];
