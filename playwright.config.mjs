// End-to-end tests in headless Debian Chromium (/usr/bin/chromium; no `npx playwright install` needed or
// possible here) against the production build served by `vite preview` (run `npx vite build` first:
// scripts/test.sh does). ADASCULPT_E2E_PORT picks another port when 4173 is busy; ADASCULPT_DIST (see
// vite.config.mjs) serves another build folder.
import { defineConfig } from '@playwright/test';

const port = Number(process.env.ADASCULPT_E2E_PORT || 4173);

export default defineConfig({
  testDir: 'e2e',
  timeout: 60_000,
  // Two browsers at a time (ADASCULPT_E2E_WORKERS): the 2-core machine's second core was idle with one.
  workers: Number(process.env.ADASCULPT_E2E_WORKERS || 2),
  retries: 0,
  forbidOnly: !!process.env.CI,
  reporter: [['list']],
  outputDir: 'test-results',
  use: {
    baseURL: `http://127.0.0.1:${port}`,
    viewport: { width: 800, height: 600 },
    launchOptions: {
      executablePath: '/usr/bin/chromium',
      // The last five keep Chromium from dialling out on this closed network. WebGL2 still works (SwiftShader).
      args: ['--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage', '--disable-background-networking',
        '--disable-component-update', '--disable-sync', '--no-first-run', '--disable-quic'],
    },
  },
  webServer: {
    command: `npx vite preview --port ${port} --strictPort`,
    url: `http://127.0.0.1:${port}/`,
    reuseExistingServer: !process.env.CI,
    timeout: 60_000,
  },
});
