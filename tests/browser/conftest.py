def pytest_addoption(parser):
    parser.addoption("--cli", required=True, help="the mocapdb binary")
    parser.addoption("--shared", required=True, help="the shared folder (datasets/)")
    parser.addoption("--screenshots", required=True, help="folder for the views' screenshots")
