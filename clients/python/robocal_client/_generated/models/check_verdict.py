from enum import StrEnum

class CheckVerdict(StrEnum):
    BASE_MOVED = "base_moved"
    CONTROLLER_CHANGED = "controller_changed"
    DRIFT = "drift"
    PASS = "pass"

    def __str__(self) -> str:
        return str(self.value)
